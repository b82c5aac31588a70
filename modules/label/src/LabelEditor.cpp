// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/label/LabelEditor.h"

#include <dynobj/core/Config.h>
#include <dynobj/core/SphericalProjection.h>
#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/FrameImages.h>
#include <dynobj/io/LabelFile.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgproc.hpp>

namespace dynobj::label {

namespace {

std::string sizeText(int rows, int cols) {
  return std::to_string(rows) + "x" + std::to_string(cols);
}

Eigen::Vector3d centroidOf(const core::LidarFrame& f, const std::vector<std::uint32_t>& pixels) {
  Eigen::Vector3d c(0, 0, 0);
  if (pixels.empty()) return c;
  for (std::uint32_t px : pixels) {
    const cv::Vec3f& p = f.xyz(static_cast<int>(px) / f.cols(), static_cast<int>(px) % f.cols());
    c += Eigen::Vector3d(p[0], p[1], p[2]);
  }
  return c / static_cast<double>(pixels.size());
}

/// The rows where an object stands on the floor are ground for the segmenter (within a few cm of
/// the ground height), so growing stops above them. Adds, column by column downwards, the ground
/// pixels right below an object pixel whose point continues it (the grower's distance and depth
/// tests): a foot continues the leg above it, while the floor below a foot is seen in front of
/// the object, much nearer, and the floor beside it is in no object pixel's column.
void addFeet(const core::LidarFrame& f, const cv::Mat_<std::uint8_t>& ground,
             const cv::Mat_<std::uint8_t>& others, const core::RegionGrowingParams& gp,
             cv::Mat_<std::uint8_t>& mask) {
  const double gap_v = f.sensor.fovSpan() / f.rows();
  for (int c = 0; c < f.cols(); c++)
    for (int r = 0; r + 1 < f.rows(); r++) {
      if (!mask(r, c) || mask(r + 1, c) || !f.isValid(r + 1, c) || !ground(r + 1, c) ||
          others(r + 1, c))
        continue;
      if (!gp.joins(f.xyz(r, c), f.range(r, c), f.xyz(r + 1, c), f.range(r + 1, c), gap_v, false))
        continue;
      mask(r + 1, c) = 255;  // and on down the column (r + 1 is visited next)
    }
}

}  // namespace

void LabelParams::visit(core::ParamVisitor& v) {
  v.value("distance", distance, {0.01, 5});
  v.value("max_extent", max_extent, {0.1, 50});
  v.value("seed_distance", seed_distance, {0.01, 5});
  v.value("cache_sweeps", cache_sweeps, {2, 10000});
  v.value("feet", feet);
}

void LabelParams::validate() const {
  core::StageParams::validate();
  growing.validate();
  ground.validate();
  ego_motion.validate();
}

const char* toString(LabelState s) {
  switch (s) {
    case LabelState::confirmed:
      return "confirmed";
    case LabelState::proposed:
      return "proposed";
    case LabelState::prelabel:
      return "prelabel";
  }
  return "confirmed";
}

LabelState labelStateFromString(const std::string& s) {
  if (s == "confirmed") return LabelState::confirmed;
  if (s == "proposed") return LabelState::proposed;
  if (s == "prelabel") return LabelState::prelabel;
  throw LabelError("unknown label state '" + s + "' (confirmed, proposed, prelabel)");
}

LabelEditor::LabelEditor(SweepSource& source, const LabelParams& params)
    : source_(source), p_(params), ground_(params.ground) {
  p_.validate();
  if (source_.size() == 0) throw LabelError(source_.describe() + " has no sweep");
  core::LidarFrame f;
  std::optional<Eigen::Isometry3d> pose;
  try {
    source_.load(0, f, pose);
  } catch (const std::exception& e) {
    throw LabelError(std::string("cannot read sweep 0: ") + e.what());
  }
  rows_ = f.rows();
  cols_ = f.cols();
  labels_.resize(source_.size());
}

std::shared_ptr<const LoadedSweep> LabelEditor::sweep(std::size_t k) {
  if (k >= size())
    throw LabelError("sweep " + std::to_string(k) + " does not exist (there are " +
                     std::to_string(size()) + ")");
  for (auto it = cache_.begin(); it != cache_.end(); ++it)
    if (it->first == k) {
      cache_.splice(cache_.begin(), cache_, it);
      return cache_.front().second;
    }
  auto s = std::make_shared<LoadedSweep>();
  try {
    source_.load(k, s->frame, s->pose);
  } catch (const std::exception& e) {
    throw LabelError("cannot read sweep " + std::to_string(k) + ": " + e.what());
  }
  if (s->frame.rows() != rows_ || s->frame.cols() != cols_)
    throw LabelError("sweep " + std::to_string(k) + " is " +
                     sizeText(s->frame.rows(), s->frame.cols()) + " but sweep 0 is " +
                     sizeText(rows_, cols_) + ": one sensor mode per session");
  ground_.segment(s->frame, s->ground);
  cache_.emplace_front(k, s);
  while (cache_.size() > static_cast<std::size_t>(p_.cache_sweeps)) cache_.pop_back();
  return s;
}

cv::Mat_<std::uint8_t> LabelEditor::others(std::size_t k, int except_id) const {
  cv::Mat_<std::uint8_t> b(rows_, cols_, std::uint8_t{0});
  for (const auto& o : labels_[k].objects) {
    if (o.id == except_id) continue;
    for (std::uint32_t px : o.pixels)
      b(static_cast<int>(px) / cols_, static_cast<int>(px) % cols_) = 255;
  }
  return b;
}

std::vector<std::uint32_t> LabelEditor::grow(std::size_t k, int row, int col, int id,
                                             double distance, double max_extent) {
  const auto s = sweep(k);
  if (row < 0 || row >= rows_ || col < 0 || col >= cols_)
    throw LabelError("pixel (" + std::to_string(row) + ", " + std::to_string(col) +
                     ") is outside the " + sizeText(rows_, cols_) + " image");
  const cv::Mat_<std::uint8_t> other = others(k, id);
  const cv::Mat_<std::uint8_t> block = cv::max(other, s->ground);
  int best = -1, best_d = 1 << 30;
  for (int dr = -1; dr <= 1; dr++)
    for (int dc = -3; dc <= 3; dc++) {
      const int r = row + dr, c = (col + dc + cols_) % cols_;
      if (r < 0 || r >= rows_ || !s->frame.isValid(r, c) || block(r, c)) continue;
      const int d = 9 * dr * dr + dc * dc;
      if (d < best_d) best_d = d, best = r * cols_ + c;
    }
  if (best < 0) {
    const bool ground = s->frame.isValid(row, col) && s->ground(row, col);
    throw LabelError("nothing to grow from at row " + std::to_string(row) + ", column " +
                     std::to_string(col) + " of sweep " + std::to_string(k) +
                     (ground ? ": that is ground" : ": no return there (or already labelled)"));
  }
  core::RegionGrowingParams gp = p_.growing;
  gp.distance = distance > 0 ? distance : p_.distance;
  gp.max_extent = max_extent > 0 ? max_extent : p_.max_extent;
  try {
    gp.validate();
  } catch (const std::exception& e) {
    throw LabelError(std::string("region growing: ") + e.what());
  }
  core::RegionGrower grower(gp);
  cv::Mat_<std::uint8_t> mask;
  cv::Mat_<int> owner;
  grower.grow(s->frame, block, {{best}}, mask, owner);
  if (p_.feet) addFeet(s->frame, s->ground, other, gp, mask);
  return io::pixelsOfMask(mask);
}

SweepLabels& LabelEditor::mutableLabels(std::size_t k) {
  if (k >= size())
    throw LabelError("sweep " + std::to_string(k) + " does not exist (there are " +
                     std::to_string(size()) + ")");
  return labels_[k];
}

const ObjectLabel* LabelEditor::object(std::size_t k, int id) const {
  for (const auto& o : labels_.at(k).objects)
    if (o.id == id) return &o;
  return nullptr;
}

void LabelEditor::setObject(std::size_t k, int id, std::vector<std::uint32_t> pixels,
                            LabelState state) {
  SweepLabels& sl = mutableLabels(k);
  if (id <= 0) throw LabelError("object ids start at 1 (got " + std::to_string(id) + ")");
  std::sort(pixels.begin(), pixels.end());
  pixels.erase(std::unique(pixels.begin(), pixels.end()), pixels.end());
  const auto n = static_cast<std::uint32_t>(rows_ * cols_);
  if (!pixels.empty() && pixels.back() >= n)
    throw LabelError("pixel " + std::to_string(pixels.back()) + " is outside the " +
                     sizeText(rows_, cols_) + " image");
  for (auto& o : sl.objects) {  // one object per pixel: the new label takes them
    if (o.id == id || pixels.empty()) continue;
    std::vector<std::uint32_t> rest;
    std::set_difference(o.pixels.begin(), o.pixels.end(), pixels.begin(), pixels.end(),
                        std::back_inserter(rest));
    o.pixels = std::move(rest);
  }
  auto it = std::find_if(sl.objects.begin(), sl.objects.end(),
                         [&](const ObjectLabel& o) { return o.id == id; });
  if (it == sl.objects.end()) {
    sl.objects.push_back(ObjectLabel{id, state, {}});
    it = sl.objects.end() - 1;
  }
  it->pixels = std::move(pixels);
  it->state = state;
  sl.objects.erase(std::remove_if(sl.objects.begin(), sl.objects.end(),
                                  [](const ObjectLabel& o) { return o.pixels.empty(); }),
                   sl.objects.end());
  std::sort(sl.objects.begin(), sl.objects.end(),
            [](const ObjectLabel& a, const ObjectLabel& b) { return a.id < b.id; });
  if (state != LabelState::confirmed) sl.reviewed = false;
  if (!info_.count(id)) info_[id] = ObjectInfo{id, "object", true};
  next_id_ = std::max(next_id_, id + 1);
  revision_++;
}

int LabelEditor::newObject(const std::string& cls, bool moving) {
  const int id = next_id_++;
  info_[id] = ObjectInfo{id, cls, moving};
  revision_++;
  return id;
}

void LabelEditor::setObjectInfo(const ObjectInfo& info) {
  if (info.id <= 0) throw LabelError("object ids start at 1");
  if (info.cls.empty() || info.cls.find_first_of("\n\r\"\\") != std::string::npos)
    throw LabelError("object class '" + info.cls + "' must be one line of plain text");
  info_[info.id] = info;
  next_id_ = std::max(next_id_, info.id + 1);
  revision_++;
}

Eigen::Isometry3d LabelEditor::motion(std::size_t from, std::size_t to, std::string& source) {
  const auto a = sweep(from), b = sweep(to);
  if (a->pose && b->pose) {
    source = "odometry";
    return a->pose->inverse() * *b->pose;
  }
  core::EgoMotionEstimator est(p_.ego_motion);
  const auto exclude = [&](std::size_t k) {
    cv::Mat_<std::uint8_t> m(rows_, cols_, std::uint8_t{0});
    for (const auto& o : labels_[k].objects)
      for (std::uint32_t px : o.pixels)
        m(static_cast<int>(px) / cols_, static_cast<int>(px) % cols_) = 255;
    return m;
  };
  cv::Mat_<float> ia, ib;
  io::intensityToU8(a->frame).convertTo(ia, CV_32F);
  io::intensityToU8(b->frame).convertTo(ib, CV_32F);
  est.estimate(a->frame, ia, exclude(from));
  const core::EgoMotion em = est.estimate(b->frame, ib, exclude(to));
  if (em.ok) {
    source = "intensity";
    return em.motion;
  }
  source = "none";
  return Eigen::Isometry3d::Identity();
}

Propagation LabelEditor::propagate(std::size_t k, int id) {
  if (k + 1 >= size()) throw LabelError("sweep " + std::to_string(k) + " is the last one");
  const ObjectLabel* obj = object(k, id);
  if (!obj)
    throw LabelError("object " + std::to_string(id) + " has no label in sweep " +
                     std::to_string(k));
  Propagation out;
  out.to = k + 1;
  if (const ObjectLabel* there = object(k + 1, id);
      there && there->state == LabelState::confirmed) {
    out.found = out.kept = true;
    out.pixels = there->pixels.size();
    return out;
  }
  const auto a = sweep(k);
  const std::vector<std::uint32_t> pixels = obj->pixels;  // copy: setObject may move the vector
  const Eigen::Vector3d c_k = centroidOf(a->frame, pixels);
  if (k > 0) {
    if (const ObjectLabel* prev = object(k - 1, id)) {
      const auto p = sweep(k - 1);
      std::string src;
      const Eigen::Isometry3d T_prev_cur = motion(k - 1, k, src);  // frame k -> frame k-1
      const Eigen::Vector3d c_prev = T_prev_cur.inverse() * centroidOf(p->frame, prev->pixels);
      const double dt = static_cast<double>(timestamp(k) - timestamp(k - 1)) * 1e-9;
      if (dt > 0) out.velocity = (c_k - c_prev) / dt;
      out.velocity.z() = 0;
    }
  }
  const Eigen::Isometry3d T = motion(k, k + 1, out.ego_motion);  // frame k+1 -> frame k
  const Eigen::Isometry3d T_inv = T.inverse();
  const double dt = static_cast<double>(timestamp(k + 1) - timestamp(k)) * 1e-9;
  const Eigen::Vector3d shift = out.velocity * dt;
  const auto b = sweep(k + 1);
  const cv::Mat_<std::uint8_t> other = others(k + 1, id);
  const cv::Mat_<std::uint8_t> block = cv::max(other, b->ground);
  const core::SphericalProjection proj(b->frame.sensor);
  std::vector<int> seeds;
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(rows_ * cols_), 0);
  const double max_d2 = p_.seed_distance * p_.seed_distance;
  for (std::uint32_t px : pixels) {
    const cv::Vec3f& v = a->frame.xyz(static_cast<int>(px) / cols_, static_cast<int>(px) % cols_);
    const Eigen::Vector3d q = T_inv * (Eigen::Vector3d(v[0], v[1], v[2]) + shift);
    int r = 0, c = 0;
    if (!proj.pixelOf(q.x(), q.y(), q.z(), r, c)) continue;
    int best = -1;
    double best_d2 = max_d2;
    for (int dr = -1; dr <= 1; dr++)
      for (int dc = -2; dc <= 2; dc++) {
        const int rr = r + dr, cc = (c + dc + cols_) % cols_;
        if (rr < 0 || rr >= rows_ || !b->frame.isValid(rr, cc) || block(rr, cc)) continue;
        const cv::Vec3f& w = b->frame.xyz(rr, cc);
        const double d2 = (Eigen::Vector3d(w[0], w[1], w[2]) - q).squaredNorm();
        if (d2 <= best_d2) best_d2 = d2, best = rr * cols_ + cc;
      }
    if (best >= 0 && !taken[static_cast<std::size_t>(best)]) {
      taken[static_cast<std::size_t>(best)] = 1;
      seeds.push_back(best);
    }
  }
  if (seeds.empty()) return out;
  core::RegionGrowingParams gp = p_.growing;
  gp.distance = p_.distance;
  gp.max_extent = p_.max_extent;
  core::RegionGrower grower(gp);
  cv::Mat_<std::uint8_t> mask;
  cv::Mat_<int> owner;
  grower.grow(b->frame, block, {seeds}, mask, owner);
  if (p_.feet) addFeet(b->frame, b->ground, other, gp, mask);
  std::vector<std::uint32_t> grown = io::pixelsOfMask(mask);
  out.found = !grown.empty();
  out.pixels = grown.size();
  if (out.found) setObject(k + 1, id, std::move(grown), LabelState::proposed);
  return out;
}

void LabelEditor::setReviewed(std::size_t k, bool reviewed) {
  SweepLabels& sl = mutableLabels(k);
  sl.reviewed = reviewed;
  if (reviewed)
    for (auto& o : sl.objects) o.state = LabelState::confirmed;
  revision_++;
}

std::size_t LabelEditor::reviewedCount() const {
  return static_cast<std::size_t>(std::count_if(labels_.begin(), labels_.end(),
                                                [](const SweepLabels& s) { return s.reviewed; }));
}

std::size_t LabelEditor::labelledCount() const {
  return static_cast<std::size_t>(std::count_if(
      labels_.begin(), labels_.end(), [](const SweepLabels& s) { return !s.objects.empty(); }));
}

std::size_t LabelEditor::loadPrelabels(const std::string& labels_file) {
  io::LabelFile f;
  try {
    f = io::LabelFile::read(labels_file);
  } catch (const std::exception& e) {
    throw LabelError(e.what());
  }
  if (f.rows != rows_ || f.cols != cols_)
    throw LabelError(labels_file + ": labels for a " + sizeText(f.rows, f.cols) +
                     " image, but the sweeps of " + source_.describe() + " are " +
                     sizeText(rows_, cols_) + " (another sensor or sensor mode?)");
  std::map<std::int64_t, std::size_t> by_time;
  for (std::size_t k = 0; k < size(); k++) by_time[timestamp(k)] = k;
  std::size_t added = 0;
  for (const auto& s : f.sweeps) {
    const auto it = by_time.find(s.timestamp_ns);
    if (it == by_time.end())
      throw LabelError(labels_file + ": sweep at " + std::to_string(s.timestamp_ns) +
                       " ns is not in " + source_.describe() + " (labels of another recording?)");
    const std::size_t k = it->second;
    if (!labels_[k].objects.empty() || labels_[k].reviewed || s.pixels.empty()) continue;
    const cv::Mat_<std::uint8_t> mask = io::maskOfPixels(s.pixels, rows_, cols_);
    cv::Mat_<int> comp;
    const int n = cv::connectedComponents(mask, comp, 8, CV_32S);
    std::vector<std::vector<std::uint32_t>> parts(static_cast<std::size_t>(std::max(0, n - 1)));
    for (std::uint32_t px : s.pixels) {
      const int l = comp(static_cast<int>(px) / cols_, static_cast<int>(px) % cols_);
      if (l > 0) parts[static_cast<std::size_t>(l - 1)].push_back(px);
    }
    for (auto& part : parts) {
      if (part.empty()) continue;
      setObject(k, newObject("detected", true), std::move(part), LabelState::prelabel);
      added++;
    }
  }
  return added;
}

std::vector<std::string> LabelEditor::outputFiles(const std::string& base) {
  return {base + ".labels", base + ".instances", base + ".session.json"};
}

void LabelEditor::save(const std::string& base, const std::string& rawlog) const {
  std::vector<std::uint8_t> reviewed(size());
  for (std::size_t k = 0; k < size(); k++) reviewed[k] = labels_[k].reviewed ? 1 : 0;
  const auto files = outputFiles(base);
  io::LabelFileWriter inst(files[1], rows_, cols_, true);
  io::LabelFileWriter dyn(files[0], rows_, cols_, false);
  inst.writeReviewed(reviewed);
  dyn.writeReviewed(reviewed);
  nlohmann::json unconfirmed = nlohmann::json::array();
  std::vector<std::pair<std::uint32_t, std::int32_t>> all;
  std::vector<std::uint32_t> moving, px;
  std::vector<std::int32_t> ids;
  for (std::size_t k = 0; k < size(); k++) {
    all.clear();
    moving.clear();
    for (const auto& o : labels_[k].objects) {
      const auto info = info_.find(o.id);
      const bool is_moving = info == info_.end() || info->second.moving;
      for (std::uint32_t p : o.pixels) {
        all.emplace_back(p, o.id);
        if (is_moving) moving.push_back(p);
      }
      if (o.state != LabelState::confirmed) unconfirmed.push_back({k, o.id, toString(o.state)});
    }
    std::sort(all.begin(), all.end());
    std::sort(moving.begin(), moving.end());
    px.clear();
    ids.clear();
    for (const auto& [p, id] : all) px.push_back(p), ids.push_back(id);
    inst.write(timestamp(k), px, ids);
    dyn.write(timestamp(k), moving);
  }
  nlohmann::json j;
  j["format"] = "dynobj-label-session v1";
  j["rawlog"] = rawlog;
  j["rows"] = rows_;
  j["cols"] = cols_;
  j["sweeps"] = size();
  j["next_id"] = next_id_;
  j["objects"] = nlohmann::json::array();
  for (const auto& [id, info] : info_)
    j["objects"].push_back({{"id", id}, {"class", info.cls}, {"moving", info.moving}});
  j["unconfirmed"] = unconfirmed;
  io::AtomicFile js(files[2]);
  js.stream() << j.dump(1) << "\n";
  inst.close();
  dyn.close();
  js.commit();
}

void LabelEditor::load(const std::string& base) {
  const auto files = outputFiles(base);
  io::LabelFile f;
  try {
    f = io::LabelFile::read(files[1]);
  } catch (const std::exception& e) {
    throw LabelError(std::string("cannot resume: ") + e.what());
  }
  if (!f.instances)
    throw LabelError(files[1] + ": not an instance file ('# dynobj-instances v1' header)");
  if (f.rows != rows_ || f.cols != cols_)
    throw LabelError(files[1] + ": labels for a " + sizeText(f.rows, f.cols) +
                     " image, but the sweeps of " + source_.describe() + " are " +
                     sizeText(rows_, cols_) + " (another sensor or sensor mode?)");
  if (f.sweeps.size() != size())
    throw LabelError(files[1] + ": " + std::to_string(f.sweeps.size()) + " sweeps, but " +
                     source_.describe() + " has " + std::to_string(size()) +
                     " (labels of another recording?)");
  for (std::size_t k = 0; k < size(); k++)
    if (f.sweeps[k].timestamp_ns != timestamp(k))
      throw LabelError(files[1] + ": sweep " + std::to_string(k) + " is at " +
                       std::to_string(f.sweeps[k].timestamp_ns) + " ns but the input's is at " +
                       std::to_string(timestamp(k)) + " ns (labels of another recording?)");
  std::vector<SweepLabels> labels(size());
  std::map<int, ObjectInfo> info;
  int next_id = 1;
  for (std::size_t k = 0; k < size(); k++) {
    std::map<int, std::vector<std::uint32_t>> by_id;
    const auto& s = f.sweeps[k];
    for (std::size_t i = 0; i < s.pixels.size(); i++) {
      if (s.ids[i] <= 0)
        throw LabelError(files[1] + ": sweep " + std::to_string(k) + " has object id " +
                         std::to_string(s.ids[i]) + " (ids start at 1)");
      by_id[s.ids[i]].push_back(s.pixels[i]);
    }
    for (auto& [id, px] : by_id) {
      labels[k].objects.push_back(ObjectLabel{id, LabelState::confirmed, std::move(px)});
      if (!info.count(id)) info[id] = ObjectInfo{id, "object", true};
      next_id = std::max(next_id, id + 1);
    }
    labels[k].reviewed = f.isReviewed(k);
  }
  std::ifstream js(files[2]);
  if (js) {
    try {
      const nlohmann::json j = nlohmann::json::parse(js);
      if (j.value("format", "") != "dynobj-label-session v1")
        throw LabelError("not a dynobj-label session file");
      next_id = std::max(next_id, j.value("next_id", 1));
      for (const auto& o : j.at("objects")) {
        const int id = o.at("id").get<int>();
        info[id] = ObjectInfo{id, o.at("class").get<std::string>(), o.at("moving").get<bool>()};
      }
      for (const auto& u : j.at("unconfirmed")) {
        const auto k = u.at(0).get<std::size_t>();
        const int id = u.at(1).get<int>();
        if (k >= size()) throw LabelError("sweep " + std::to_string(k) + " does not exist");
        for (auto& o : labels[k].objects)
          if (o.id == id) o.state = labelStateFromString(u.at(2).get<std::string>());
      }
    } catch (const std::exception& e) {
      throw LabelError(files[2] + ": " + e.what());
    }
  }
  labels_ = std::move(labels);
  info_ = std::move(info);
  next_id_ = next_id;
  revision_++;
}

}  // namespace dynobj::label
