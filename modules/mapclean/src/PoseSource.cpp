// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/PoseSource.h"

#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/PoseConversion.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/poses/CPose3DPDF.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>

namespace dynobj::mapclean {
namespace {

std::string seconds(std::int64_t ns) {
  char b[40];
  std::snprintf(b, sizeof(b), "%.6f s", static_cast<double>(ns) * 1e-9);
  return b;
}

std::string scanName(const Scan& s) {
  return "scan " + std::to_string(s.index) + " (" + s.where +
         ", t = " + seconds(s.frame.timestamp_ns) + ")";
}

class OdometryPoses : public PoseSource {
 public:
  Eigen::Isometry3d pose(const Scan& s, const core::EgoMotion&) override {
    if (!s.odometry)
      throw std::runtime_error(
          "no odometry (CObservationOdometry) before " + scanName(s) +
          ": choose another pose source (--poses ego, a TUM file or a simplemap)");
    return *s.odometry * s.mount;
  }
  std::string describe() const override { return "rawlog odometry"; }
};

class EgoPoses : public PoseSource {
 public:
  Eigen::Isometry3d pose(const Scan& s, const core::EgoMotion& ego) override {
    pose_ = first_ ? s.mount : Eigen::Isometry3d(pose_ * ego.motion);
    first_ = false;
    return pose_;
  }
  std::string describe() const override { return "detector ego-motion"; }

 private:
  bool first_ = true;
  Eigen::Isometry3d pose_ = Eigen::Isometry3d::Identity();
};

class ViewpointPoses : public PoseSource {
 public:
  Eigen::Isometry3d pose(const Scan& s, const core::EgoMotion&) override {
    if (!s.viewpoint)
      throw std::runtime_error("--poses viewpoint needs a KTH DynamicMap PCD folder as input (" +
                               scanName(s) + " has no VIEWPOINT)");
    return *s.viewpoint;
  }
  std::string describe() const override { return "PCD VIEWPOINT"; }
};

/// Poses by timestamp; shared by the TUM and simplemap sources.
class StampedPoses {
 public:
  StampedPoses(std::string file, std::vector<io::TimedPose> poses, std::int64_t tol_ns)
      : file_(std::move(file)), poses_(std::move(poses)), tol_(tol_ns) {
    std::sort(poses_.begin(), poses_.end(),
              [](const auto& a, const auto& b) { return a.timestamp_ns < b.timestamp_ns; });
    if (poses_.empty()) throw std::runtime_error("'" + file_ + "' holds no pose");
  }
  const io::TimedPose* find(std::int64_t t) const { return io::findPose(poses_, t, tol_); }
  /// The latest pose before t, or null.
  const io::TimedPose* before(std::int64_t t) const {
    const io::TimedPose* best = nullptr;
    for (const auto& p : poses_)
      if (p.timestamp_ns <= t) best = &p;
    return best;
  }
  [[noreturn]] void missing(const Scan& s, const std::string& hint = "") const {
    const std::int64_t t = s.frame.timestamp_ns;
    if (t > poses_.back().timestamp_ns + tol_)
      throw std::runtime_error("'" + file_ + "' has " + std::to_string(poses_.size()) +
                               " poses, fewer than the scans: none for " + scanName(s) +
                               " (its last pose is at " + seconds(poses_.back().timestamp_ns) +
                               ")" + hint);
    const auto* near = io::findPose(poses_, t, INT64_MAX / 4);
    throw std::runtime_error("'" + file_ + "': no pose within " + seconds(tol_) + " of " +
                             scanName(s) + " (nearest at " + seconds(near->timestamp_ns) +
                             "): the timestamps do not match" + hint);
  }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<io::TimedPose> poses_;
  std::int64_t tol_;
};

class TumPoses : public PoseSource {
 public:
  TumPoses(const std::string& file, const PoseSourceOptions& o)
      : poses_(file, io::readPoseFile(file, io::PoseFormat::Tum),
               static_cast<std::int64_t>(o.tolerance_s * 1e9)),
        robot_(o.tum_robot_poses) {}
  Eigen::Isometry3d pose(const Scan& s, const core::EgoMotion&) override {
    const auto* p = poses_.find(s.frame.timestamp_ns);
    if (!p) poses_.missing(s);
    return robot_ ? Eigen::Isometry3d(p->pose * s.mount) : p->pose;
  }
  std::string describe() const override { return "TUM file '" + poses_.file() + "'"; }

 private:
  StampedPoses poses_;
  bool robot_;
};

std::vector<io::TimedPose> simplemapKeyframes(const std::string& file) {
  mrpt::maps::CSimpleMap sm;
  if (!sm.loadFromFile(file)) throw std::runtime_error("cannot read simplemap '" + file + "'");
  std::vector<io::TimedPose> out;
  for (std::size_t i = 0; i < sm.size(); i++) {
    const auto [pdf, sf] = std::as_const(sm).get(i);
    if (!pdf || !sf || sf->size() == 0) continue;
    io::TimedPose p;
    p.timestamp_ns = mrptio::toUnixNs((*sf->begin())->timestamp);
    p.pose = mrptio::toIsometry(pdf->getMeanVal());
    out.push_back(p);
  }
  return out;
}

class SimplemapPoses : public PoseSource {
 public:
  SimplemapPoses(const std::string& file, const PoseSourceOptions& o)
      : keyframes_(file, simplemapKeyframes(file), static_cast<std::int64_t>(o.tolerance_s * 1e9)),
        ego_available_(o.ego_available) {}
  Eigen::Isometry3d pose(const Scan& s, const core::EgoMotion& ego) override {
    const std::int64_t t = s.frame.timestamp_ns;
    if (const auto* k = keyframes_.find(t)) {  // a keyframe: its robot pose, and its odometry
      last_kf_ = k->pose;
      last_kf_odometry_ = s.odometry;
      since_kf_ = Eigen::Isometry3d::Identity();
      return k->pose * s.mount;
    }
    since_kf_ = since_kf_ * ego.motion;  // the detector's ego-motion since the keyframe
    const auto* prev = keyframes_.before(t);
    if (!prev || !last_kf_) keyframes_.missing(s);
    if (s.odometry && last_kf_odometry_)
      return *last_kf_ * (last_kf_odometry_->inverse() * *s.odometry) * s.mount;
    if (!ego_available_)
      keyframes_.missing(s,
                         "; scans between keyframes need odometry in the rawlog, or the "
                         "detector's ego-motion (not with --labels)");
    ego_between_ = true;
    return *last_kf_ * s.mount * since_kf_;
  }
  std::string describe() const override {
    return "simplemap '" + keyframes_.file() + "'" +
           (ego_between_ ? " (ego-motion between keyframes: no odometry)" : "");
  }

 private:
  StampedPoses keyframes_;
  bool ego_available_;
  bool ego_between_ = false;
  std::optional<Eigen::Isometry3d> last_kf_, last_kf_odometry_;
  Eigen::Isometry3d since_kf_ = Eigen::Isometry3d::Identity();
};

/// "auto": the first scan decides (odometry, else a PCD VIEWPOINT, else the detector's ego-motion).
class AutoPoses : public PoseSource {
 public:
  explicit AutoPoses(bool ego_available) : ego_available_(ego_available) {}
  Eigen::Isometry3d pose(const Scan& s, const core::EgoMotion& ego) override {
    if (!chosen_) {
      if (s.odometry) {
        chosen_ = std::make_unique<OdometryPoses>();
        why_ = "the rawlog has odometry";
      } else if (s.viewpoint) {
        chosen_ = std::make_unique<ViewpointPoses>();
        why_ = "the input has a VIEWPOINT per scan";
      } else if (ego_available_) {
        chosen_ = std::make_unique<EgoPoses>();
        why_ = "the input has no odometry";
      } else {
        throw std::runtime_error("no odometry (CObservationOdometry) before " + scanName(s) +
                                 ", and the detector's ego-motion does not run with --labels: "
                                 "choose a pose source with --poses (a TUM file or a simplemap)");
      }
    }
    return chosen_->pose(s, ego);
  }
  std::string describe() const override {
    if (!chosen_) return "automatic";
    return chosen_->describe() + " (chosen: " + why_ + ")";
  }

 private:
  bool ego_available_;
  std::unique_ptr<PoseSource> chosen_;
  std::string why_;
};

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() &&
         s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

}  // namespace

std::unique_ptr<PoseSource> makePoseSource(const std::string& spec, const PoseSourceOptions& opts) {
  if (spec == "auto") return std::make_unique<AutoPoses>(opts.ego_available);
  if (spec == "odometry") return std::make_unique<OdometryPoses>();
  if (spec == "ego") return std::make_unique<EgoPoses>();
  if (spec == "viewpoint") return std::make_unique<ViewpointPoses>();
  const bool tum = endsWith(spec, ".tum") || endsWith(spec, ".txt");
  const bool simplemap = endsWith(spec, ".simplemap") || endsWith(spec, ".simplemap.gz");
  if (!tum && !simplemap)
    throw std::runtime_error("poses '" + spec +
                             "': unknown format (expected auto, odometry, ego, viewpoint, "
                             "a TUM file *.tum|*.txt or an MRPT *.simplemap[.gz])");
  if (!std::filesystem::is_regular_file(spec))
    throw std::runtime_error("poses file '" + spec + "' does not exist");
  if (tum) return std::make_unique<TumPoses>(spec, opts);
  return std::make_unique<SimplemapPoses>(spec, opts);
}

}  // namespace dynobj::mapclean
