// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/DynamicObjectDetector.h"

#include <algorithm>
#include <chrono>
#include <cstring>
#include <future>
#include <opencv2/imgproc.hpp>
#include <utility>

#include "dynobj/core/Config.h"

namespace dynobj::core {
namespace {

/// Stage timings [ms]: lap() returns the time since the previous lap (or construction).
class StageClock {
 public:
  double lap() {
    const auto now = Clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }
  double total() const {
    return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now(), last_ = start_;
};

/// The horizontal box (x, y) of the points of each seed set: its low and high corners.
std::vector<std::pair<Eigen::Vector2f, Eigen::Vector2f>> horizontalBoxes(
    const LidarFrame& frame, const std::vector<std::vector<int>>& seeds) {
  std::vector<std::pair<Eigen::Vector2f, Eigen::Vector2f>> boxes;
  for (const std::vector<int>& pixels : seeds) {
    Eigen::Vector2f lo(1e9f, 1e9f), hi(-1e9f, -1e9f);
    for (int px : pixels) {
      const cv::Vec3f& p = frame.pointAt(px);
      lo = lo.cwiseMin(Eigen::Vector2f(p[0], p[1]));
      hi = hi.cwiseMax(Eigen::Vector2f(p[0], p[1]));
    }
    boxes.emplace_back(lo, hi);
  }
  return boxes;
}

std::vector<Eigen::Vector3d> centroidsOf(const std::vector<Cluster>& clusters) {
  std::vector<Eigen::Vector3d> c;
  c.reserve(clusters.size());
  for (const Cluster& k : clusters) c.push_back(k.centroid);
  return c;
}

}  // namespace

DetectionResult DetectionResult::clone() const {
  DetectionResult r = *this;
  r.dynamic = dynamic.clone();
  r.features = features.clone();
  r.seeds = seeds.clone();
  r.ground = ground.clone();
  return r;
}

void PipelineParams::visit(ParamVisitor& v) {
  v.value("threads", threads, {1, 2});
}

void DetectorParams::load(const mrpt::config::CConfigFileBase& c, const std::string& prefix) {
  DetectorParams p = *this;  // all or nothing: *this changes only if every section is valid
  p.forEachStage([&](const char* name, StageParams& stage) {
    try {
      stage.loadFromConfigFile(c, prefix + name);
    } catch (const ParameterError& e) {
      const std::string what = e.what();
      throw ParameterError(what.rfind("[", 0) == 0 ? what : "[" + prefix + name + "] " + what);
    }
  });
  *this = p;
}

void DetectorParams::save(mrpt::config::CConfigFileBase& c, const std::string& prefix) const {
  forEachStage([&](const char* name, const StageParams& stage) {
    stage.saveToConfigFile(c, prefix + name);
  });
}

void DetectorParams::validate() const {
  forEachStage([](const char*, const StageParams& stage) { stage.validate(); });
}

DynamicObjectDetector::DynamicObjectDetector(const DetectorParams& params)
    : params_(params),
      foreground_(params.foreground),
      ground_(params.ground),
      ego_(params.ego_motion),
      refiner_(params.ego_refinement),
      clusterer_(params.clustering),
      associator_(params.association),
      movement_(params.movement),
      free_space_(params.free_space, static_cast<std::size_t>(params.free_space.history() + 1)),
      tracks_(params.tracking, params.movement.window),
      grower_(params.region_growing),
      split_{params.association.split_radius,
             params.clustering.horizontal_distance / params.clustering.vertical_distance,
             params.clustering.horizontal_distance,
             params.clustering.min_points,
             params.association.split_min_share,
             params.association.split_match_radius,
             params.association.split_rest_majority,
             params.association.split_hold_back},
      chain_(static_cast<std::size_t>(
          std::max((params.movement.window + 1) * (params.tracking.max_missed + 1) + 2,
                   params.free_space.history() + 2))),
      check_(params.frame_check),
      worker_(params.pipeline.threads > 1 && std::thread::hardware_concurrency() > 1) {
  params_.validate();
}

void DynamicObjectDetector::reset() {
  forgetMotion();
  tracks_.reset();
  check_.reset();
  frame_index_ = -1;
  sweep_ = -1;
  last_stamp_ = 0;
}

void DynamicObjectDetector::forgetMotion() {
  ego_.reset();
  refiner_.reset();
  tracks_.tracks().clear();
  chain_.clear();
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
  } else if (em.ok || frame_index_ > 0) {
    // Beyond the paper: refined on the range images' geometry, from the feature estimate or,
    // when the features failed, from the constant-velocity guess.
    const EgoRefinement g = refiner_.refine(frame, em.ok ? em.motion : last_motion_, prev_dynamic_);
    if (g.ok) {
      em.motion = g.motion;
      em.refined = true;
      if (!em.ok) em.source = "geometric";
      em.ok = true;
    } else if (!em.ok) {
      em.motion = last_motion_;  // keep tracking on a constant-velocity guess, flagged unreliable
      em.source = "constant-velocity";
    }
  }
  if (em.ok) last_motion_ = em.motion;
  return em;
}

const DetectionResult& DynamicObjectDetector::process(
    const LidarFrame& frame, const std::optional<Eigen::Isometry3d>& external_motion) {
  StageClock clock;
  const double dt = beginFrame(frame);  // seconds since the previous frame
  if (dt == 0) return result_;          // a time reversal or a duplicate: not used (FrameCheck)
  DetectionResult& r = result_;

  // III-A-2 and III-B-1, Eq. (2)-(5): the normalised intensity f, then the ego-motion since the
  // last frame from its features, beside the ground, the features (III-A-2) and the clusters
  // (III-B-2): nothing before III-B-3 reads the motion.
  egoMotionBesideClusters(frame, external_motion);
  chain_.push(frame_index_, r.ego_motion.motion, r.ego_motion.ok || frame_index_ == 0);
  clock.lap();  // the stages above timed themselves; the wait for the ego-motion is in none

  // III-B-3, Eq. (8)-(13): the tracks predicted into this frame, then GNN / Hungarian association.
  const std::vector<int> split = associate(frame, dt);
  r.timings.association = clock.lap();

  // III-C-1, III-C-2, Eq. (14)-(23): movement over each track's window; dynamic tracks seed
  const std::vector<std::vector<int>> seeds = dynamicSeeds(frame, dt);
  rememberShapes(frame, frame_index_, clusters_, split, tracks_.tracks());
  r.timings.movement = clock.lap();

  // III-C-3, Eq. (24)-(25): region growing from the seeds, stopped at the ground.
  const std::vector<int> grown = grow(frame, dt, seeds);
  r.timings.region_growing = clock.lap();

  endFrame(frame, grown);
  r.timings.total = clock.total();
  return r;
}

void DynamicObjectDetector::egoMotionBesideClusters(
    const LidarFrame& frame, const std::optional<Eigen::Isometry3d>& external_motion) {
  DetectionResult& r = result_;
  // The worker (threads = 2) normalises the intensity, hands f over and goes on with the
  // ego-motion; this thread clears the masks and finds the ground meanwhile.
  std::promise<void> normalized;
  std::future<void> f_ready = normalized.get_future();
  worker_.start([&] {
    StageClock ego_clock;
    try {
      foreground_.normalize(frame);
    } catch (...) {
      normalized.set_exception(std::current_exception());
      throw;
    }
    r.timings.foreground = ego_clock.lap();
    normalized.set_value();
    r.ego_motion = egoMotion(frame, external_motion);
    r.timings.ego_motion = ego_clock.lap();
  });
  try {
    segmentGround(frame);
    f_ready.get();  // the features need f
    featuresAndClusters(frame);
  } catch (...) {
    worker_.drain();  // the worker works on `frame` and `r`: finished before they go
    throw;
  }
  worker_.wait();
}

void DynamicObjectDetector::segmentGround(const LidarFrame& frame) {
  StageClock clock;
  // This frame's masks, cleared here on the main thread while the worker starts.
  DetectionResult& r = result_;
  r.dynamic.create(frame.range.size());
  r.dynamic.setTo(0);
  r.seeds.create(frame.range.size());
  r.seeds.setTo(0);
  owner_.create(frame.range.size());
  owner_.setTo(-1);
  // Ground pixels: region growing never enters them (III-C-3), and no features lie on them.
  ground_.segment(frame, r.ground);
  r.timings.ground = clock.lap();
}

void DynamicObjectDetector::featuresAndClusters(const LidarFrame& frame) {
  StageClock clock;
  DetectionResult& r = result_;
  // III-A-2, Eq. (2)-(4): foreground feature pixels t = B(f - h, theta).
  const bool no_ground = params_.foreground.exclude_ground;
  foreground_.extractNormalized(frame, no_ground ? r.ground : cv::Mat_<std::uint8_t>(), r.features);
  r.timings.foreground += clock.lap();
  // III-B-2, Eq. (6)-(7): clusters of the foreground points.
  clusterer_.cluster(frame, r.features, clusters_, &weak_, &dropped_);
  r.timings.clustering = clock.lap();
}

std::vector<int> DynamicObjectDetector::grow(const LidarFrame& frame, double dt,
                                             const std::vector<std::vector<int>>& seeds) {
  // Beyond the paper (§8): not into what the lookback frame saw on a surface, nor nearer to an
  // object at rest than to the mover's own seeds.
  const std::vector<Box2> boxes = horizontalBoxes(frame, seeds);
  const std::vector<int> grown =
      grower_.grow(frame, result_.ground, seeds, result_.dynamic, owner_,
                   nearerTheMover(frame, seeds, boxes, pastSurfaceTest(frame, dt, seeds, boxes)));
  result_.seen_static = grower_.refused();
  return grown;
}

double DynamicObjectDetector::beginFrame(const LidarFrame& frame) {
  DetectionResult& r = result_;
  r.warnings.clear();
  const FrameCheck::Verdict verdict = check_.check(frame, ++sweep_, r.warnings);
  r.objects.clear();
  r.timestamp_ns = frame.timestamp_ns;
  if (verdict == FrameCheck::Verdict::Skip) {  // the sweep before's dynamic pixels, no objects
    if (r.dynamic.size() != frame.range.size())
      r.dynamic = cv::Mat_<std::uint8_t>::zeros(frame.range.size());
    r.ego_motion = EgoMotion{};
    r.timings = StageTimings{};
    return 0;
  }
  if (verdict == FrameCheck::Verdict::Restart) forgetMotion();
  r.seen_static.clear();
  r.frame_index = ++frame_index_;
  const double dt =
      (verdict == FrameCheck::Verdict::Use && last_stamp_ != 0 && frame.timestamp_ns > last_stamp_)
          ? 1e-9 * static_cast<double>(frame.timestamp_ns - last_stamp_)
          : 1.0 / frame.sensor.frequency;
  last_stamp_ = frame.timestamp_ns;
  if (prev_dynamic_.size() != frame.range.size()) prev_dynamic_.release();
  return dt;
}

std::vector<int> DynamicObjectDetector::associate(const LidarFrame& frame, double dt) {
  tracks_.predict(result_.ego_motion.motion, dt);  // Eq. (8)
  const std::vector<Eigen::Vector3d> predicted = tracks_.predicted();
  // Eq. (9)-(13), beyond the paper: the movers first, a wider gate for a track with no velocity.
  std::vector<int> cluster_to_track = associator_.associateMoversFirst(
      centroidsOf(clusters_), predicted, tracks_.gates(associator_, dt), tracks_.movers());
  carveMovers(frame, predicted, cluster_to_track);
  // Beyond the paper: a cluster holding a mover and an object at rest is split between them.
  held_.clear();
  const std::vector<int> split = splitSettled(split_, frame, frame_index_, chain_, tracks_.tracks(),
                                              predicted, clusters_, cluster_to_track, &held_);
  std::sort(held_.begin(), held_.end());
  findWeakSeeds(predicted, cluster_to_track);
  tracks_.update(frame_index_, clusters_, cluster_to_track);
  return split;
}

std::vector<std::size_t> DynamicObjectDetector::unmatchedMovers(
    const std::vector<int>& cluster_to_track) const {
  const std::vector<Track>& tracks = tracks_.tracks();
  std::vector<char> matched(tracks.size(), 0);
  for (int t : cluster_to_track)
    if (t >= 0) matched[static_cast<std::size_t>(t)] = 1;
  std::vector<std::size_t> out;
  for (std::size_t t = 0; t < tracks.size(); t++)
    if (tracks[t].dynamic && !matched[t]) out.push_back(t);
  return out;
}

void DynamicObjectDetector::carveMovers(const LidarFrame& frame,
                                        const std::vector<Eigen::Vector3d>& predicted,
                                        std::vector<int>& cluster_to_track) {
  if (!params_.association.carve_dropped || dropped_.empty() || !chain_.contains(frame_index_))
    return;
  const long past = std::max(chain_.oldest(), frame_index_ - free_space_.params().lookback);
  if (past >= frame_index_) return;
  const std::vector<Track>& tracks = tracks_.tracks();
  Cluster one;
  one.pixels.resize(1);
  for (const std::size_t t : unmatchedMovers(cluster_to_track)) {
    const Eigen::Vector3d& p = predicted[t];
    const double reach = std::clamp(tracks[t].radius, 0.3, 3.0) + 0.2;
    Cluster c;
    for (int px : dropped_) {
      const cv::Vec3f& q = frame.pointAt(px);
      const double dx = q[0] - p.x(), dy = q[1] - p.y();
      if (dx * dx + dy * dy > reach * reach) continue;
      one.pixels[0] = px;
      if (free_space_.evidence(frame, frame_index_, one, past, chain_).free > 0)
        c.pixels.push_back(px);
    }
    if (static_cast<int>(c.pixels.size()) < params_.clustering.min_points) continue;
    computeClusterShape(frame, c);
    clusters_.push_back(std::move(c));
    cluster_to_track.push_back(static_cast<int>(t));
  }
}

void DynamicObjectDetector::findWeakSeeds(const std::vector<Eigen::Vector3d>& predicted,
                                          const std::vector<int>& cluster_to_track) {
  weak_seeds_.clear();
  if (weak_.empty()) return;
  std::vector<int> movers;  // dynamic tracks without a cluster, and where they are expected
  std::vector<Eigen::Vector3d> expected;
  for (const std::size_t t : unmatchedMovers(cluster_to_track)) {
    movers.push_back(tracks_.tracks()[t].id);
    expected.push_back(predicted[t]);
  }
  if (movers.empty()) return;
  // The same gated association (Eq. 8-13), between the weak clusters and these tracks only.
  const std::vector<int> a = associator_.associate(centroidsOf(weak_), expected);
  for (std::size_t m = 0; m < weak_.size(); m++)
    if (a[m] >= 0) weak_seeds_.emplace_back(movers[static_cast<std::size_t>(a[m])], m);
}

std::vector<std::vector<int>> DynamicObjectDetector::dynamicSeeds(const LidarFrame& frame,
                                                                  double dt) {
  std::vector<std::vector<int>> seeds;
  seed_track_.clear();
  for (Track& tr : tracks_.tracks()) {
    if (tr.cluster < 0) continue;
    const Cluster& c = clusters_[static_cast<std::size_t>(tr.cluster)];
    MovementDecision d = movement_.analyse(tr.window, chain_, c, dt, tr.atRest());
    free_space_.review(frame, frame_index_, c, chain_, dt, d, result_.ground);  // beyond the paper
    tracks_.decide(tr, d);                                                      // with hysteresis
    if (!tr.dynamic) continue;
    seeds.emplace_back();
    for (int px : c.pixels)  // but a resting object's points held back from it (SettledSplit.h)
      if (!std::binary_search(held_.begin(), held_.end(), px)) seeds.back().push_back(px);
    seed_track_.push_back(tr.id);
    for (int px : seeds.back()) result_.seeds(px / frame.cols(), px % frame.cols()) = 255;
  }
  // Beyond the paper (§5): a dynamic track coasting through this sweep seeds from its weak
  // cluster, if it found one (no observation: its state and decisions stay as they were).
  for (const auto& [id, m] : weak_seeds_) {
    const auto tr = std::find_if(tracks_.tracks().begin(), tracks_.tracks().end(),
                                 [id = id](const Track& t) { return t.id == id; });
    if (tr == tracks_.tracks().end() || tr->cluster >= 0 || !tr->dynamic) continue;
    seeds.push_back(weak_[m].pixels);
    seed_track_.push_back(id);
    for (int px : weak_[m].pixels) result_.seeds(px / frame.cols(), px % frame.cols()) = 255;
  }
  if (grower_.params().keep_out_settled) {  // beyond the paper: a mover beside one at rest (§9)
    for (const Track& tr : tracks_.tracks())
      if (tr.cluster >= 0 && tr.atRest())
        RegionGrower::keepOut(clusters_[static_cast<std::size_t>(tr.cluster)].pixels, owner_);
    RegionGrower::keepOut(held_, owner_);  // and its part held back from a mover's cluster
  }
  return seeds;
}

RegionGrower::Admit DynamicObjectDetector::pastSurfaceTest(
    const LidarFrame& frame, double dt, const std::vector<std::vector<int>>& seeds,
    const std::vector<Box2>& boxes) const {
  if (!grower_.params().past_surface_check) return {};
  const long past = std::max(chain_.oldest(), frame_index_ - free_space_.params().lookback);
  const auto view = free_space_.pastView(frame, frame_index_, past, chain_);
  if (!view) return {};
  // Per seed set: did its object travel farther than its own horizontal extent since `past`?
  std::vector<char> clear(seeds.size(), 0);
  bool any = false;
  for (std::size_t s = 0; s < seeds.size(); s++) {
    const auto tr = std::find_if(tracks_.tracks().begin(), tracks_.tracks().end(),
                                 [id = seed_track_[s]](const Track& t) { return t.id == id; });
    if (tr == tracks_.tracks().end() || seeds[s].empty()) continue;
    const auto& [lo, hi] = boxes[s];
    const double travelled = tr->velocity().norm() * dt * static_cast<double>(frame_index_ - past);
    clear[s] = travelled > static_cast<double>((hi - lo).norm());
    any = any || clear[s];
  }
  if (!any) return {};
  return [this, &frame, v = *view, clear](std::size_t obj, int px) {
    return !clear[obj] || !free_space_.sawSurfaceThen(v, frame.pointAt(px));
  };
}

RegionGrower::Admit DynamicObjectDetector::nearerTheMover(
    const LidarFrame& frame, const std::vector<std::vector<int>>& seeds,
    const std::vector<Box2>& boxes, RegionGrower::Admit then) const {
  const double radius = grower_.params().nearer_rest_radius;
  if (radius <= 0 || !grower_.params().keep_out_settled) return then;
  // Per seed set, the feature points of the objects at rest (Track::atRest) whose cluster's box
  // comes within `radius` of the seeds' box.
  std::vector<std::vector<int>> beside(seeds.size());
  for (std::size_t s = 0; s < seeds.size(); s++) {
    if (seeds[s].empty()) continue;
    const auto& [lo, hi] = boxes[s];
    const auto r = static_cast<float>(radius);
    for (const Track& tr : tracks_.tracks()) {
      if (tr.cluster < 0 || !tr.atRest()) continue;
      const Cluster& c = clusters_[static_cast<std::size_t>(tr.cluster)];
      if (c.min.x() <= hi.x() + r && c.max.x() >= lo.x() - r && c.min.y() <= hi.y() + r &&
          c.max.y() >= lo.y() - r)
        beside[s].insert(beside[s].end(), c.pixels.begin(), c.pixels.end());
    }
  }
  return RegionGrower::nearerOwnSeeds(frame, seeds, beside, radius, std::move(then));
}

void DynamicObjectDetector::endFrame(const LidarFrame& frame, const std::vector<int>& grown) {
  // The ego-motion's memory of this frame on the worker, beside the rest (they share nothing).
  worker_.start([&] {
    refiner_.remember(frame, result_.ground);
    ego_.dropPreviousOn(result_.dynamic);  // no keypoints on this frame's movers next time
  });
  try {
    collectObjects(frame, grown);
    check_.egoMotion(result_.ego_motion.ok || chain_.oldest() == frame_index_, sweep_,
                     result_.warnings);  // the first sweep has no motion to fail
    free_space_.remember(frame_index_, frame, result_.ground);
  } catch (...) {
    worker_.drain();
    throw;
  }
  worker_.wait();
  result_.dynamic.copyTo(prev_dynamic_);
}

void DynamicObjectDetector::collectObjects(const LidarFrame& frame, const std::vector<int>& grown) {
  // The grown region of each dynamic object, in one pass over the dynamic mask (set exactly where
  // the owner image is), eight pixels at a time where none is set.
  std::vector<Cluster> regions(seed_track_.size());
  const int* own = owner_.ptr<int>(0);
  const std::uint8_t* dyn = result_.dynamic.ptr<std::uint8_t>(0);
  const int n = owner_.rows * owner_.cols;
  for (int i = 0; i < n;) {
    std::uint64_t eight = 0;
    if (i + 8 <= n) std::memcpy(&eight, dyn + i, 8);
    if (i + 8 <= n && eight == 0) {
      i += 8;
      continue;
    }
    if (dyn[i] && own[i] >= 0) regions[static_cast<std::size_t>(own[i])].pixels.push_back(i);
    i++;
  }
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
    o.at_rest = tr.atRest();
    o.age = tr.age;
    o.cluster = c.pixels;
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
