// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/PointTruth.h"

#include <dynobj/io/CloudFolder.h>
#include <dynobj/io/SemanticKittiLabel.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "dynobj/eval/SequenceMetrics.h"

namespace dynobj::eval {
namespace {

/// Is `p` (sensor frame) inside `b` grown by `grow` on every side?
bool inside(const TruthBox& b, const Eigen::Vector3d& p, double grow,
            Eigen::Vector3d* local = nullptr) {
  const Eigen::Vector3d q = b.pose.inverse() * p;
  if (local) *local = q;
  return std::abs(q.x()) <= b.size.x() / 2 + grow && std::abs(q.y()) <= b.size.y() / 2 + grow &&
         std::abs(q.z()) <= b.size.z() / 2 + grow;
}

}  // namespace

void BoxTruthParams::validate() const {
  if (!(moving_speed > 0)) throw std::invalid_argument("moving_speed must be > 0");
  if (!(static_speed >= 0 && static_speed <= moving_speed))
    throw std::invalid_argument("static_speed must be in [0, moving_speed]");
  if (!(speed_window > 0)) throw std::invalid_argument("speed_window must be > 0");
  if (!(min_span >= 0)) throw std::invalid_argument("min_span must be >= 0");
  if (!(band >= 0)) throw std::invalid_argument("band must be >= 0");
}

BoxTruth::BoxTruth(std::vector<std::vector<TruthBox>> boxes, BoxTruthParams params,
                   std::function<bool(const Eigen::Vector3d&)> annotated, std::string description)
    : boxes_(std::move(boxes)),
      p_(params),
      annotated_(std::move(annotated)),
      description_(std::move(description)) {
  p_.validate();
  for (const auto& sweep : boxes_)
    for (const TruthBox& b : sweep) classes_[b.track] = b.cls;
}

std::unique_ptr<BoxTruth> BoxTruth::fromKitti(const std::string& label_file,
                                              const std::string& calib_file,
                                              const BoxTruthParams& p, int image_width,
                                              int image_height) {
  const std::vector<io::KittiBox> rows = io::readKittiTrackingLabels(label_file);
  const io::KittiCalib calib = io::readKittiCalib(calib_file);
  const Eigen::Isometry3d velo_to_rect = calib.veloToRect();
  const Eigen::Isometry3d rect_to_velo = velo_to_rect.inverse();
  // The box's own axes (x length, y width, z up) in KITTI's box frame (x length, y down, z width).
  Eigen::Matrix3d axes;
  axes << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  std::vector<std::vector<TruthBox>> boxes;
  for (const io::KittiBox& r : rows) {
    if (r.track_id < 0 || r.type == "DontCare") continue;
    if (static_cast<std::size_t>(r.frame) >= boxes.size()) boxes.resize(r.frame + 1);
    TruthBox b;
    b.track = r.track_id;
    b.cls = r.type;
    b.size = Eigen::Vector3d(r.l, r.w, r.h);
    Eigen::Isometry3d in_rect = Eigen::Isometry3d::Identity();
    in_rect.linear() = Eigen::AngleAxisd(r.ry, Eigen::Vector3d::UnitY()).toRotationMatrix() * axes;
    in_rect.translation() = r.bottom - Eigen::Vector3d(0, r.h / 2, 0);  // y points down
    b.pose = rect_to_velo * in_rect;
    boxes[r.frame].push_back(b);
  }
  const Eigen::Matrix<double, 3, 4> P2 = calib.P2;
  auto annotated = [P2, velo_to_rect, image_width, image_height](const Eigen::Vector3d& x) {
    const Eigen::Vector3d c = velo_to_rect * x;
    if (c.z() <= 0.1) return false;
    const Eigen::Vector3d u = P2 * c.homogeneous();
    const double col = u.x() / u.z(), row = u.y() / u.z();
    return col >= 0 && col < image_width && row >= 0 && row < image_height;
  };
  return std::make_unique<BoxTruth>(std::move(boxes), p, annotated,
                                    "KITTI tracking boxes '" + label_file + "'");
}

std::unique_ptr<BoxTruth> BoxTruth::fromBoxTrackFile(const std::string& path,
                                                     const BoxTruthParams& p) {
  std::vector<std::vector<TruthBox>> boxes;
  for (const io::BoxTrackRow& r : io::readBoxTracks(path)) {
    if (r.sweep >= boxes.size()) boxes.resize(r.sweep + 1);
    TruthBox b;
    b.track = r.track;
    b.cls = r.cls;
    b.size = r.size;
    b.pose = Eigen::Translation3d(r.centre) * Eigen::AngleAxisd(r.yaw, Eigen::Vector3d::UnitZ());
    boxes[r.sweep].push_back(b);
  }
  return std::make_unique<BoxTruth>(std::move(boxes), p, nullptr, "box tracks '" + path + "'");
}

void BoxTruth::setSensorPoses(const std::vector<Eigen::Isometry3d>& poses,
                              const std::vector<std::int64_t>& stamps) {
  if (poses.size() != stamps.size())
    throw std::invalid_argument("setSensorPoses: poses and stamps differ in number");
  if (boxes_.size() > poses.size())
    throw EvaluationError(description_ + " has boxes for sweep " +
                          std::to_string(boxes_.size() - 1) + " but the recording has " +
                          std::to_string(poses.size()) + " sweeps");
  // Each track's trajectory in the world: (sweep, time [s], horizontal centre).
  struct Sample {
    std::size_t sweep, box;
    double t;
    Eigen::Vector2d c;
  };
  std::map<int, std::vector<Sample>> traj;
  for (std::size_t k = 0; k < boxes_.size(); k++)
    for (std::size_t i = 0; i < boxes_[k].size(); i++) {
      const Eigen::Vector3d c = poses[k] * boxes_[k][i].pose.translation();
      traj[boxes_[k][i].track].push_back(
          {k, i, 1e-9 * static_cast<double>(stamps[k] - stamps[0]), c.head<2>()});
    }
  state_.assign(boxes_.size(), {});
  for (std::size_t k = 0; k < boxes_.size(); k++)
    state_[k].assign(boxes_[k].size(), PointLabel::Unknown);
  tracks_.clear();
  for (const auto& [track, s] : traj) {
    TrackMotion m;
    m.track = track;
    m.cls = classes_.at(track);
    for (const Sample& x : s) {
      // The samples within half a window on each side; their first and last span the window.
      const Sample* a = &x;
      const Sample* b = &x;
      for (const Sample& y : s) {
        if (y.t < x.t - p_.speed_window / 2 || y.t > x.t + p_.speed_window / 2) continue;
        if (y.t < a->t) a = &y;
        if (y.t > b->t) b = &y;
      }
      double speed = std::numeric_limits<double>::quiet_NaN();
      PointLabel state = PointLabel::Unknown;
      if (b->t - a->t >= std::max(p_.min_span, 1e-6)) {
        speed = (b->c - a->c).norm() / (b->t - a->t);
        if (speed >= p_.moving_speed)
          state = PointLabel::Moving;
        else if (speed < p_.static_speed)
          state = PointLabel::Static;
      }
      state_[x.sweep][x.box] = state;
      m.sweeps.push_back(x.sweep);
      m.speed.push_back(speed);
      m.state.push_back(state);
    }
    tracks_.push_back(std::move(m));
  }
}

SweepTruth BoxTruth::truthOf(std::size_t k, const core::PointCloud& pts) const {
  if (state_.size() != boxes_.size())
    throw std::logic_error("BoxTruth::truthOf before setSensorPoses");
  SweepTruth t;
  t.label.assign(pts.size(), PointLabel::Static);
  t.object.assign(pts.size(), -1);
  const std::vector<TruthBox> none;
  const std::vector<TruthBox>& boxes = k < boxes_.size() ? boxes_[k] : none;
  for (std::size_t i = 0; i < pts.size(); i++) {
    const Eigen::Vector3d p(pts.x[i], pts.y[i], pts.z[i]);
    if (annotated_ && !annotated_(p)) {
      t.label[i] = PointLabel::Unknown;
      continue;
    }
    for (std::size_t j = 0; j < boxes.size(); j++) {
      const TruthBox& b = boxes[j];
      const PointLabel state = state_[k][j];
      // A static box's points are static (the default); a moving or undecided one's are its
      // own, bar the band; the band of a moving box is unknown.
      const double grow = state == PointLabel::Static ? 0.0 : p_.band;
      Eigen::Vector3d q;
      if (!inside(b, p, grow, &q)) continue;
      const bool core_part = std::abs(q.x()) <= b.size.x() / 2 &&
                             std::abs(q.y()) <= b.size.y() / 2 &&
                             q.z() >= -b.size.z() / 2 + p_.band && q.z() <= b.size.z() / 2;
      if (state == PointLabel::Moving && core_part) {
        t.label[i] = PointLabel::Moving;
        t.object[i] = b.track;
        break;  // inside a moving box wins over any band
      }
      if (state != PointLabel::Static) t.label[i] = PointLabel::Unknown;
    }
  }
  return t;
}

std::string BoxTruth::className(int object) const {
  const auto it = classes_.find(object);
  return it == classes_.end() ? "unknown" : it->second;
}

SemanticKittiTruth::SemanticKittiTruth(const std::string& dir) : dir_(dir) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(dir))
    throw EvaluationError("'" + dir + "' is not a folder of SemanticKITTI .label files");
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".label") files_.push_back(e.path().string());
  if (files_.empty()) throw EvaluationError("'" + dir + "' holds no .label file");
  std::sort(files_.begin(), files_.end(), io::naturalLess);
}

SweepTruth SemanticKittiTruth::truthOf(std::size_t k, const core::PointCloud& pts) const {
  if (k >= files_.size())
    throw EvaluationError("'" + dir_ + "' has " + std::to_string(files_.size()) +
                          " .label files, so no labels for sweep " + std::to_string(k));
  const std::vector<std::uint32_t> raw = io::readSemanticKittiLabels(files_[k]);
  if (raw.size() != pts.size())
    throw EvaluationError(files_[k] + ": " + std::to_string(raw.size()) + " labels, but sweep " +
                          std::to_string(k) + " has " + std::to_string(pts.size()) + " points");
  SweepTruth t;
  t.label.resize(raw.size());
  t.object.assign(raw.size(), -1);
  for (std::size_t i = 0; i < raw.size(); i++) {
    const auto semantic = static_cast<std::uint16_t>(raw[i] & 0xFFFFu);
    if (semantic == io::semantic_kitti::kUnlabeled) {
      t.label[i] = PointLabel::Unknown;
    } else if (io::semantic_kitti::isMoving(semantic)) {
      t.label[i] = PointLabel::Moving;
      // The object: its instance id with its class (instances are numbered per class).
      const int id = static_cast<int>((raw[i] >> 16) << 9 | (semantic - 251u));
      t.object[i] = id;
      classes_.emplace(id, io::semantic_kitti::movingClassName(semantic));
    } else {
      t.label[i] = PointLabel::Static;
    }
  }
  return t;
}

std::string SemanticKittiTruth::className(int object) const {
  const auto it = classes_.find(object);
  return it == classes_.end() ? "moving" : it->second;
}

std::unique_ptr<PointTruthSource> openPointTruth(const std::string& path, const std::string& calib,
                                                 const BoxTruthParams& p) {
  namespace fs = std::filesystem;
  if (!fs::exists(path)) throw EvaluationError("ground truth '" + path + "' does not exist");
  if (fs::is_directory(path)) {
    if (!calib.empty())
      throw EvaluationError("--calib is for KITTI tracking labels, but '" + path +
                            "' is a folder (SemanticKITTI labels)");
    return std::make_unique<SemanticKittiTruth>(path);
  }
  if (fs::path(path).extension() == ".csv") return BoxTruth::fromBoxTrackFile(path, p);
  if (calib.empty())
    throw EvaluationError("'" + path +
                          "' is read as KITTI tracking labels: give their calibration (--calib "
                          "calib.txt)");
  return BoxTruth::fromKitti(path, calib, p);
}

std::vector<std::uint32_t> toSemanticKitti(const SweepTruth& t, const PointTruthSource& source) {
  std::vector<std::uint32_t> out(t.label.size());
  for (std::size_t i = 0; i < out.size(); i++) {
    switch (t.label[i]) {
      case PointLabel::Static:
        out[i] = io::semantic_kitti::kStatic;
        break;
      case PointLabel::Unknown:
        out[i] = io::semantic_kitti::kUnlabeled;
        break;
      case PointLabel::Moving:
        out[i] = io::semantic_kitti::movingClassOf(source.className(t.object[i])) |
                 (static_cast<std::uint32_t>(t.object[i] & 0xFFFF) << 16);
        break;
    }
  }
  return out;
}

}  // namespace dynobj::eval
