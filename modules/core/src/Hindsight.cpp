// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/Hindsight.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "dynobj/core/Config.h"
#include "dynobj/core/DynamicObjectDetector.h"

namespace dynobj::core {
namespace {

template <class Objects>  // std::vector<TrackedObject>, const or not
auto* findTrack(Objects& objects, int id) {
  for (auto& o : objects)
    if (o.id == id) return &o;
  return static_cast<decltype(&objects[0])>(nullptr);
}

/// One object's clusters from viewpoints up to `lag` apart differ in extent by up to this factor
/// (real HDL-64 city-22: an oncoming car 5.35 m now, 6.11 m 0.3 s before; VLP-16 `parking`: a
/// car 5.27 m now, 7.40 m 0.5 s before; a walker merged with a bench: 0.5 m now, 1.8 m then).
constexpr double kViewSpread = 1.5;

/// start_check: an earlier sweep counts as standing when its speed into it is below this share
/// of its speed out of it ...
constexpr double kStartRatio = 0.25;
constexpr std::size_t kRestSteps = 2;  ///< ... on each of this many steps before it

/// [m] way_along: a track that went less far than this has no direction to measure along.
constexpr double kMinWent = 0.01;

/// Horizontal extent of an object's box [m].
double extent(const TrackedObject& o) {
  return (o.box_max - o.box_min).head<2>().norm();
}

/// Seconds from frame a to frame b (timestamps, else the frame count at the sensor's rate).
double secondsBetween(const Hindsight::Held& a, const Hindsight::Held& b, std::size_t frames) {
  const std::int64_t ta = a.result->timestamp_ns, tb = b.result->timestamp_ns;
  if (ta > 0 && tb > ta) return 1e-9 * static_cast<double>(tb - ta);
  return static_cast<double>(frames) / b.frame->sensor.frequency;
}

}  // namespace

void HindsightParams::visit(ParamVisitor& v) {
  v.value("lag", lag);
  v.value("min_speed", min_speed);
  v.value("speed_window", speed_window);
  v.value("min_dynamic", min_dynamic);
  v.value("start_check", start_check);
  v.value("max_growth", max_growth);
  v.value("settle_distance", settle_distance);
  v.value("stop_check", stop_check);
  v.value("rest_speed", rest_speed);
  v.value("later_surface_check", later_surface_check);
  v.value("later_surface_points", later_surface_points);
  v.value("way_along", way_along);
}

void HindsightParams::validate() const {
  requireInRange("lag", lag, 0, 60);
  requireInRange("min_speed", min_speed, 0, 100);
  requireInRange("speed_window", speed_window, 0, 60);
  requireInRange("min_dynamic", min_dynamic, 0, 60);
  requirePositive("max_growth", max_growth);
  requireInRange("settle_distance", settle_distance, 0, 1000);
  requireInRange("rest_speed", rest_speed, 0, 100);
}

Hindsight::Hindsight(const HindsightParams& p, const RegionGrowingParams& growing,
                     const FreeSpaceParams& free_space)
    : p_(p), grower_(growing), free_space_(free_space) {
  p_.validate();
  free_space_.validate();
}

RegionGrower::Admit Hindsight::laterSurfaceTest(const std::vector<Held>& held, std::size_t j,
                                                const TrackedObject& now, const TrackedObject& then,
                                                const Eigen::Vector3d& here,
                                                const Eigen::Isometry3d& T_jk) {
  if (!p_.later_surface_check) return {};
  // It cannot have been there itself: it has travelled farther than its extent since (or, point
  // by point, the point lies outside where it is now).
  const std::size_t k = held.size() - 1;
  if (!p_.later_surface_points && (here - path_.front().second).head<2>().norm() <= extent(then))
    return {};
  const LidarFrame& newest = *held[k].frame;
  if (!proj_ || proj_->sensor().rows != newest.rows() || proj_->sensor().cols != newest.cols())
    proj_.emplace(newest.sensor);
  const cv::Mat_<std::uint8_t>& ground = held[k].result->ground;
  const Eigen::Isometry3d T_kj = T_jk.inverse();
  const FreeSpaceCheck::PastView later{
      &newest.range, ground.size() == newest.range.size() ? &ground : nullptr, T_kj};
  if (!p_.later_surface_points)
    return [this, &f = *held[j].frame, later](std::size_t, int px) {
      return !FreeSpaceCheck::sawSurfaceIn(*proj_, free_space_, later, f.pointAt(px));
    };
  const double margin = grower_.params().distance;
  const Eigen::Vector2d lo = now.box_min.head<2>().array() - margin;
  const Eigen::Vector2d hi = now.box_max.head<2>().array() + margin;
  return [this, &f = *held[j].frame, later, lo, hi](std::size_t, int px) {
    const cv::Vec3f& p = f.pointAt(px);
    const Eigen::Vector2d q = (later.T * Eigen::Vector3d(p[0], p[1], p[2])).head<2>();
    const bool where_now = (q.array() >= lo.array()).all() && (q.array() <= hi.array()).all();
    return where_now || !FreeSpaceCheck::sawSurfaceIn(*proj_, free_space_, later, p);
  };
}

void Hindsight::keepOutSettled(const DetectionResult& r, const LidarFrame& f, int except_id) {
  owner_.create(f.range.size());
  owner_.setTo(RegionGrower::kFree);
  RegionGrower::keepOut(r.seen_static, owner_);  // past_surface_check refused them
  if (!grower_.params().keep_out_settled) return;
  for (const TrackedObject& s : r.objects)
    if (s.at_rest && !s.dynamic && s.id != except_id) RegionGrower::keepOut(s.cluster, owner_);
}

bool Hindsight::movingAt(const std::vector<Held>& held, std::size_t j, const TrackedObject& then,
                         const Eigen::Vector3d& here, const Eigen::Isometry3d& T_jk,
                         double& out_speed) const {
  // Its speed out of this sweep, to the next later sweep that saw it, against its speed into it
  // over the kRestSteps sweeps before (each in the newest frame's coordinates). Standing here
  // and starting after it: every step in is slow. Moving here: the steps in are about as fast
  // as the step out (an accelerating car one sweep after it set off: 1/3 of it), and a centroid
  // that lags for one sweep (a view that changes) does not make a rest of two. The speed out is
  // the fastest met so far going back: once a sweep at rest was flagged (its centroid drifts as
  // the view changes), the step out of the sweep before it is that drift, not the start.
  const auto& [j1, p1] = path_.back();
  out_speed =
      std::max(out_speed, (p1 - here).head<2>().norm() / secondsBetween(held[j], held[j1], j1 - j));
  const double out = out_speed;
  Eigen::Isometry3d T_ik = T_jk;
  Eigen::Vector3d later = here;
  std::size_t steps = 0;
  for (std::size_t i = j; i > 0 && steps < kRestSteps; i--, steps++) {
    const TrackedObject* seen = findTrack(held[i - 1].result->objects, then.id);
    if (!seen) break;  // not seen then
    T_ik = held[i].result->ego_motion.motion * T_ik;
    const Eigen::Vector3d at = T_ik.inverse() * seen->centroid;
    if ((later - at).head<2>().norm() / secondsBetween(held[i - 1], held[i], 1) >=
        kStartRatio * out)
      return true;
    later = at;
  }
  if (steps == kRestSteps) return false;  // slow on every step before it: standing
  // Fewer steps in (the oldest held sweeps, or not seen just before): the track's own speed
  // then decides, if the track was as old as those steps: its Kalman filter remembers the sweeps
  // before (crowd, a walker standing for 5 s at the oldest held sweep: 0.07 m/s then, 2.1 m/s
  // out, was flagged with its 3360 points). A younger track has no speed yet: flagged.
  if (then.age <= static_cast<int>(kRestSteps)) return true;
  return then.velocity.norm() >= kStartRatio * out;
}

int Hindsight::heldFrames(double frequency) const {
  return static_cast<int>(std::ceil(p_.lag * frequency - 1e-9));
}

long Hindsight::revise(const std::vector<Held>& held, bool last) {
  if (held.size() < 2) return 0;
  const auto start = std::chrono::steady_clock::now();
  const std::size_t k = held.size() - 1;
  DetectionResult& now = *held[k].result;
  long added = 0;
  // The newest frame's dynamic run reaches min_dynamic in this many sweeps (one at least).
  const int trusted = std::max(
      1, static_cast<int>(std::ceil(p_.min_dynamic * held[k].frame->sensor.frequency - 1e-9)));
  for (const TrackedObject& o : now.objects) {
    if (!o.dynamic) continue;
    // T_{j<-k}: the current frame's coordinates seen from the earlier frame j.
    Eigen::Isometry3d T_jk = Eigen::Isometry3d::Identity();
    int run = 1;  // sweeps the track has been seen dynamic in, up to this one
    bool revising = false;
    double out_speed = 0;  // start_check: the fastest speed out met going back
    path_.clear();         // where the track was seen, in frame k's coordinates, newest first
    path_.emplace_back(k, o.centroid);
    for (std::size_t j = k; j-- > 0;) {
      T_jk = held[j + 1].result->ego_motion.motion * T_jk;
      DetectionResult& r = *held[j].result;
      TrackedObject* earlier = findTrack(r.objects, o.id);
      if (!earlier) continue;  // not seen then (coasting)
      const Eigen::Vector3d here = T_jk.inverse() * earlier->centroid;
      if (earlier->dynamic) {
        path_.emplace_back(j, here);
        // Still in the run; or, revising, an earlier run reached: it was revised then.
        if (revising || ++run > trusted) break;  // a longer run was trusted before
        continue;
      }
      // The sweep before the run: revised once, when the run becomes trusted, or at the end of
      // the recording, where nothing will tell a short run from a flicker any more.
      if (!revising && run != trusted && !(last && run < trusted)) break;
      revising = true;
      // Its speed from here: over speed_window, to the first later sweep that far on (the
      // newest when none is, or when speed_window = 0).
      std::size_t to = 0;
      for (std::size_t i = path_.size(); p_.speed_window > 0 && i-- > 1;) {
        const std::size_t j2 = path_[i].first;
        if (secondsBetween(held[j], held[j2], j2 - j) >= p_.speed_window - 1e-9) {
          to = i;
          break;
        }
      }
      const std::size_t j2 = path_[to].first;
      // ... along where it went from here, to the newest sweep (way_along): a centroid that
      // drifts sideways as the view of a parked car turns is not the car setting off.
      const Eigen::Vector2d step = (path_[to].second - here).head<2>();
      const Eigen::Vector2d went = (path_.front().second - here).head<2>();
      const double way =
          p_.way_along && went.norm() > kMinWent ? step.dot(went.normalized()) : step.norm();
      if (way < p_.min_speed * secondsBetween(held[j], held[j2], j2 - j)) break;  // not moving yet
      if (extent(*earlier) > kViewSpread * extent(o) + p_.max_growth) break;      // merged then
      if (p_.start_check && !movingAt(held, j, *earlier, here, T_jk, out_speed))
        break;  // about to start
      const LidarFrame& f = *held[j].frame;
      keepOutSettled(r, f, o.id);
      const RegionGrower::Admit later = laterSurfaceTest(held, j, o, *earlier, here, T_jk);
      std::vector<int> seeds = earlier->cluster;
      if (later && p_.later_surface_points)  // its own points, merged with someone standing
        seeds.erase(
            std::remove_if(seeds.begin(), seeds.end(), [&later](int px) { return !later(0, px); }),
            seeds.end());
      const int grown = grower_.grow(f, r.ground, {seeds}, r.dynamic, owner_, later)[0];
      for (int px : seeds) r.seeds(px / f.cols(), px % f.cols()) = 255;
      earlier->dynamic = true;
      earlier->points = grown;
      added += grown;
      path_.emplace_back(j, here);
    }
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  now.timings.hindsight += ms;
  now.timings.total += ms;
  return added;
}

bool Hindsight::stoppedAt(const std::vector<Held>& held, const TrackedObject& o) const {
  // The mirror of start_check: on each of the kRestSteps steps out of this sweep (to the next
  // later sweeps that saw it, path_), slower than a quarter of the track's speed (its Kalman
  // velocity, which still has the walk in it for a few sweeps after a stop): it stood here.
  if (path_.size() < kRestSteps + 1 || path_[1].first != 1) return false;  // seen next: a verdict
  // Or both steps together slower than rest_speed: the net way, in which a centroid's jitter
  // does not add up, judged like the tracker's stop ([movement] stop_speed).
  const auto& [j0, p0] = path_[0];
  const auto& [jn, pn] = path_[kRestSteps];
  if ((pn - p0).head<2>().norm() < p_.rest_speed * secondsBetween(held[j0], held[jn], jn - j0))
    return true;
  const double ref = o.velocity.norm();
  for (std::size_t s = 0; s < kRestSteps; s++) {
    const auto& [ja, pa] = path_[s];
    const auto& [jb, pb] = path_[s + 1];
    if ((pb - pa).head<2>().norm() / secondsBetween(held[ja], held[jb], jb - ja) >=
        kStartRatio * ref)
      return false;
  }
  return true;
}

int Hindsight::settle(const std::vector<Held>& held) {
  if ((p_.settle_distance <= 0 && !p_.stop_check) || held.size() < 2) return 0;
  const auto start = std::chrono::steady_clock::now();
  DetectionResult& first = *held[0].result;
  int unflagged = 0;
  for (TrackedObject& o : first.objects) {
    if (!o.dynamic) continue;
    // Where the track is in the later held frames that see it, carried into the first frame
    // (T_{0<-j}); no verdict across a failed ego-motion.
    Eigen::Isometry3d T_0j = Eigen::Isometry3d::Identity();
    double way = -1, span = 0;
    path_.clear();  // the first frame and the later ones that see the track, oldest first
    path_.emplace_back(0, o.centroid);
    for (std::size_t j = 1; j < held.size(); j++) {
      const DetectionResult& r = *held[j].result;
      if (!r.ego_motion.ok) break;
      T_0j = T_0j * r.ego_motion.motion;
      const TrackedObject* later = findTrack(r.objects, o.id);
      if (!later) continue;
      path_.emplace_back(j, T_0j * later->centroid);
      way = std::max(way, (path_.back().second - o.centroid).head<2>().norm());
      span = secondsBetween(held[0], held[j], j);
    }
    const bool settled = p_.settle_distance > 0 && way >= 0 && span >= 0.5 * p_.lag - 1e-9 &&
                         way < p_.settle_distance;
    if (!settled && !(p_.stop_check && stoppedAt(held, o))) continue;
    o.dynamic = false;
    unflagged++;
  }
  if (unflagged > 0) {  // the mask again, from the objects still dynamic
    const LidarFrame& f = *held[0].frame;
    std::vector<std::vector<int>> seeds;
    for (const TrackedObject& o : first.objects)
      if (o.dynamic) seeds.push_back(o.cluster);
    first.dynamic.setTo(0);
    first.seeds.setTo(0);
    keepOutSettled(first, f, -1);
    const std::vector<int> grown = grower_.grow(f, first.ground, seeds, first.dynamic, owner_);
    std::size_t s = 0;
    for (TrackedObject& o : first.objects) {
      if (!o.dynamic) continue;
      o.points = grown[s++];
      for (int px : o.cluster) first.seeds(px / f.cols(), px % f.cols()) = 255;
    }
  }
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  first.timings.hindsight += ms;
  first.timings.total += ms;
  return unflagged;
}

}  // namespace dynobj::core
