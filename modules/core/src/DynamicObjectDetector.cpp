// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/DynamicObjectDetector.h"

#include <chrono>
#include <opencv2/imgproc.hpp>

#include "dynobj/core/Config.h"

namespace dynobj::core {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point& t) {
  const auto now = Clock::now();
  const double ms = std::chrono::duration<double, std::milli>(now - t).count();
  t = now;
  return ms;
}

}  // namespace

void DetectorParams::load(const ::mrpt::config::CConfigFileBase& c, const std::string& prefix) {
  DetectorParams p = *this;  // all or nothing: *this changes only if every section is valid
  auto section = [&](::mrpt::config::CLoadableOptions& stage, const std::string& name) {
    try {
      stage.loadFromConfigFile(c, prefix + name);
    } catch (const ParameterError& e) {
      const std::string what = e.what();
      throw ParameterError(what.rfind("[", 0) == 0 ? what : "[" + prefix + name + "] " + what);
    }
  };
  section(p.foreground, "foreground");
  p.exclude_ground_features =
      readBool(c, prefix + "foreground", "exclude_ground", p.exclude_ground_features);
  section(p.ground, "ground");
  section(p.ego_motion, "ego_motion");
  section(p.clustering, "clustering");
  section(p.association, "association");
  section(p.movement, "movement");
  section(p.free_space, "free_space");
  section(p.tracking, "tracking");
  section(p.region_growing, "region_growing");
  *this = p;
}

void DetectorParams::save(::mrpt::config::CConfigFileBase& c, const std::string& prefix) const {
  foreground.saveToConfigFile(c, prefix + "foreground");
  c.write(prefix + "foreground", "exclude_ground", exclude_ground_features);
  ground.saveToConfigFile(c, prefix + "ground");
  ego_motion.saveToConfigFile(c, prefix + "ego_motion");
  clustering.saveToConfigFile(c, prefix + "clustering");
  association.saveToConfigFile(c, prefix + "association");
  movement.saveToConfigFile(c, prefix + "movement");
  free_space.saveToConfigFile(c, prefix + "free_space");
  tracking.saveToConfigFile(c, prefix + "tracking");
  region_growing.saveToConfigFile(c, prefix + "region_growing");
}

void DetectorParams::validate() const {
  foreground.validate();
  ground.validate();
  ego_motion.validate();
  clustering.validate();
  association.validate();
  movement.validate();
  free_space.validate();
  tracking.validate();
  region_growing.validate();
}

DynamicObjectDetector::DynamicObjectDetector(const DetectorParams& params)
    : params_(params),
      foreground_(params.foreground),
      ground_(params.ground),
      ego_(params.ego_motion),
      clusterer_(params.clustering),
      associator_(params.association),
      movement_(params.movement),
      free_space_(params.free_space, static_cast<std::size_t>(params.free_space.lookback + 1)),
      tracks_(params.tracking, params.movement.window),
      grower_(params.region_growing),
      chain_(static_cast<std::size_t>(
          std::max((params.movement.window + 1) * (params.tracking.max_missed + 1) + 2,
                   params.free_space.lookback + 2))) {
  params_.validate();
}

void DynamicObjectDetector::reset() {
  ego_.reset();
  tracks_.reset();
  chain_.clear();
  frame_index_ = -1;
  last_stamp_ = 0;
  last_motion_ = Eigen::Isometry3d::Identity();
  prev_dynamic_.release();
}

EgoMotion DynamicObjectDetector::egoMotion(const LidarFrame& frame,
                                           const std::optional<Eigen::Isometry3d>& external) {
  // Keypoints on last frame's dynamic objects are excluded (they would bias the motion).
  EgoMotion em = ego_.estimate(frame, foreground_.normalized(), prev_dynamic_);
  if (external) {
    em.motion = *external;
    em.ok = true;
    em.source = "external";
  } else if (!em.ok && frame_index_ > 0) {
    em.motion = last_motion_;  // keep tracking on a constant-velocity guess, flagged unreliable
    em.source = "constant-velocity";
  }
  if (em.ok) last_motion_ = em.motion;
  return em;
}

const DetectionResult& DynamicObjectDetector::process(
    const LidarFrame& frame, const std::optional<Eigen::Isometry3d>& external_motion) {
  auto t = Clock::now();
  const auto t0 = t;
  DetectionResult& r = result_;
  r.objects.clear();
  r.timestamp_ns = frame.timestamp_ns;
  r.frame_index = ++frame_index_;
  const double dt = (last_stamp_ != 0 && frame.timestamp_ns > last_stamp_)
                        ? 1e-9 * static_cast<double>(frame.timestamp_ns - last_stamp_)
                        : 1.0 / frame.sensor.frequency;
  last_stamp_ = frame.timestamp_ns;
  if (prev_dynamic_.size() != frame.range.size()) prev_dynamic_.release();

  // Ground pixels: region growing never enters them (III-C-3), and no features lie on them.
  ground_.segment(frame, ground_mask_);
  r.timings.ground = msSince(t);

  // III-A-2, Eq. (2)-(4): foreground feature pixels t = B(f - h, theta).
  foreground_.extract(
      frame, params_.exclude_ground_features ? ground_mask_ : cv::Mat_<std::uint8_t>(), r.features);
  r.timings.foreground = msSince(t);

  // III-B-1, Eq. (5): ego-motion between the previous frame and this one.
  r.ego_motion = egoMotion(frame, external_motion);
  chain_.push(frame_index_, r.ego_motion.motion, r.ego_motion.ok || frame_index_ == 0);
  r.timings.ego_motion = msSince(t);

  // III-B-2, Eq. (6)-(7): clusters of the foreground points.
  clusterer_.cluster(frame, r.features, clusters_);
  r.timings.clustering = msSince(t);

  // III-B-3, Eq. (8)-(13): tracks predicted into this frame, then GNN / Hungarian association.
  tracks_.predict(r.ego_motion.motion, dt);
  std::vector<Eigen::Vector3d> centroids;
  centroids.reserve(clusters_.size());
  for (const Cluster& c : clusters_) centroids.push_back(c.centroid);
  tracks_.update(frame_index_, clusters_, associator_.associate(centroids, tracks_.predicted()));
  r.timings.association = msSince(t);

  // III-C-1 and III-C-2, Eq. (14)-(23): movement over the sliding window, outliers rejected.
  std::vector<std::vector<int>> seeds;
  seed_track_.clear();
  for (Track& tr : tracks_.tracks()) {
    if (tr.cluster < 0) continue;
    const Cluster& c = clusters_[static_cast<std::size_t>(tr.cluster)];
    MovementDecision d = movement_.analyse(tr.window, chain_, c, dt);
    if (d.moving()) {  // beyond the paper: was the space it occupies now free at the window start?
      const long past = std::max(chain_.oldest(), frame_index_ - params_.free_space.lookback);
      const Eigen::Vector3d shift = d.velocity * dt * static_cast<double>(frame_index_ - past);
      const FreeSpaceEvidence e =
          free_space_.evidence(frame, frame_index_, c, past, chain_, shift);
      // A long object exempted from Eq. (23) as a rigid mover (a car) must prove its motion: a
      // background strip framed by moving occluders also "moves" rigidly, but no free space
      // was ever seen where it is.
      d.static_surface =
          d.rigid ? !e.provesMotion(params_.free_space) : !e.supportsMotion(params_.free_space);
    }
    tracks_.decide(tr, d);
    if (tr.dynamic) {
      seeds.push_back(c.pixels);
      seed_track_.push_back(tr.id);
    }
  }
  r.timings.movement = msSince(t);

  // III-C-3, Eq. (24)-(25): region growing from the accepted clusters, stopped at the ground.
  r.dynamic.create(frame.range.size());
  r.dynamic.setTo(0);
  r.seeds.create(frame.range.size());
  r.seeds.setTo(0);
  for (const auto& s : seeds)
    for (int px : s) r.seeds(px / frame.cols(), px % frame.cols()) = 255;
  owner_.create(frame.range.size());
  owner_.setTo(-1);
  const std::vector<int> grown = grower_.grow(frame, ground_mask_, seeds, r.dynamic, owner_);
  r.timings.region_growing = msSince(t);

  collectObjects(frame, grown);
  free_space_.remember(frame_index_, frame);
  ego_.dropPreviousOn(r.dynamic);
  r.dynamic.copyTo(prev_dynamic_);
  r.timings.total = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
  return r;
}

void DynamicObjectDetector::collectObjects(const LidarFrame& frame, const std::vector<int>& grown) {
  // The grown region of each dynamic object, in one pass over the owner image.
  std::vector<Cluster> regions(seed_track_.size());
  const int* own = owner_.ptr<int>(0);
  for (int i = 0; i < owner_.rows * owner_.cols; i++)
    if (own[i] >= 0) regions[static_cast<std::size_t>(own[i])].pixels.push_back(i);
  for (const Track& tr : tracks_.tracks()) {
    if (tr.cluster < 0) continue;
    const Cluster& c = clusters_[static_cast<std::size_t>(tr.cluster)];
    TrackedObject o;
    o.id = tr.id;
    o.centroid = c.centroid;
    o.velocity = tr.velocity();
    o.box_min = c.min;
    o.box_max = c.max;
    o.points = static_cast<int>(c.pixels.size());
    o.dynamic = tr.dynamic;
    o.age = tr.age;
    const auto it = std::find(seed_track_.begin(), seed_track_.end(), tr.id);
    if (it != seed_track_.end()) {  // a dynamic object: its extent is the grown region
      const auto obj = static_cast<std::size_t>(it - seed_track_.begin());
      o.points = grown[obj];
      Cluster& region = regions[obj];
      if (!region.pixels.empty()) {
        computeClusterShape(frame, region);
        o.box_min = region.min;
        o.box_max = region.max;
      }
    }
    result_.objects.push_back(o);
  }
}

}  // namespace dynobj::core
