// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/Hindsight.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "dynobj/core/Config.h"
#include "dynobj/core/DetectionResult.h"

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

/// fill_gaps / fill_before: fewer points than this about where an unseen object was are noise.
constexpr std::size_t kMinFill = 2;

/// fill_gaps / fill_before: does `v` see a surface (not its ground) within the free-space
/// tolerance of `p` (a point carried in by v.T), at its pixel or one beside it in its row or
/// column? Wider than FreeSpaceCheck::sawSurfaceIn: a fill is refused what may stand there.
bool surfaceNear(const SphericalProjection& proj, const FreeSpaceParams& free_space,
                 const FreeSpaceCheck::PastView& v, const cv::Vec3f& p) {
  const Eigen::Vector3d q = v.T * Eigen::Vector3d(p[0], p[1], p[2]);
  int r = -1, c = -1;
  if (!proj.pixelOf(q.x(), q.y(), q.z(), r, c)) return false;
  const double range = q.norm(), tolerance = free_space.tolerance(range);
  const cv::Mat_<float>& seen = *v.ranges;
  for (const auto& [dr, dc] : {std::pair{0, 0}, {0, -1}, {0, 1}, {-1, 0}, {1, 0}}) {
    const int rr = r + dr, cc = (c + dc + seen.cols) % seen.cols;
    if (rr < 0 || rr >= seen.rows || seen(rr, cc) <= 0 || (v.ground && (*v.ground)(rr, cc)))
      continue;
    if (std::abs(seen(rr, cc) - range) <= tolerance) return true;
  }
  return false;
}

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
  v.value("lag", lag, {0, 60});
  v.value("min_speed", min_speed, {0, 100});
  v.value("speed_window", speed_window, {0, 60});
  v.value("min_dynamic", min_dynamic, {0, 60});
  v.value("start_check", start_check);
  v.value("max_growth", max_growth, kPositive);
  v.value("stop_check", stop_check);
  v.value("rest_speed", rest_speed, {0, 100});
  v.value("later_surface_check", later_surface_check);
  v.value("later_surface_points", later_surface_points);
  v.value("way_along", way_along);
  v.value("fill_gaps", fill_gaps);
  v.value("fill_before", fill_before);
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
  projectionFor(newest);
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

const SphericalProjection& Hindsight::projectionFor(const LidarFrame& f) {
  if (!proj_ || proj_->sensor().rows != f.rows() || proj_->sensor().cols != f.cols())
    proj_.emplace(f.sensor);
  return *proj_;
}

int Hindsight::fillUnseen(const std::vector<Held>& held, std::size_t j, const TrackedObject& o,
                          const Eigen::Vector3d& at, const Eigen::Isometry3d& T_jk,
                          bool need_proof) {
  const LidarFrame& f = *held[j].frame;
  DetectionResult& r = *held[j].result;
  const Eigen::Vector3d c = T_jk * at;  // where it was, in frame j's coordinates
  const double reach = 0.5 * extent(o) + grower_.params().distance;
  const double rho = c.head<2>().norm();
  if (rho <= reach) return 0;
  const double half_height = 0.5 * (o.box_max.z() - o.box_min.z()) + grower_.params().distance;
  keepOutSettled(r, f, o.id);
  const bool ground = r.ground.size() == f.range.size();
  // The columns within its reach (Eq. 1), every row: the non-ground points near where it was.
  const int cols = f.cols();
  const int half =
      std::min((cols - 1) / 2,
               static_cast<int>(std::ceil(std::asin(reach / rho) / (2.0 * M_PI) * cols)) + 1);
  const int c0 = projectionFor(f).columnOf(c.x(), c.y());
  std::vector<int> seeds;
  for (int row = 0; row < f.rows(); row++)
    for (int dc = -half; dc <= half; dc++) {
      const int col = (c0 + dc + cols) % cols;
      if (!f.isValid(row, col) || (ground && r.ground(row, col)) || r.dynamic(row, col) ||
          owner_(row, col) != RegionGrower::kFree)
        continue;
      const cv::Vec3f& p = f.xyz(row, col);
      if (std::hypot(p[0] - c.x(), p[1] - c.y()) <= reach && std::abs(p[2] - c.z()) <= half_height)
        seeds.push_back(row * cols + col);
    }
  // Not what the newest held frame still sees there (later_surface_check, point by point).
  const RegionGrower::Admit later = laterSurfaceTest(held, j, o, o, at, T_jk);
  if (later)
    seeds.erase(
        std::remove_if(seeds.begin(), seeds.end(), [&later](int px) { return !later(0, px); }),
        seeds.end());
  if (seeds.size() < kMinFill) return 0;
  // Where it was must have been left free: the nearest held frames by which it was farther than
  // its extent away must not see a surface at half of its points (one before its first sighting
  // must even see through half of them), nor at any point it takes.
  const std::vector<FreeSpaceCheck::PastView> judges =
      judgesOf(held, j, o.velocity.norm(), extent(o) + grower_.params().distance);
  const Gone gone = verdict(f, judges, seeds);
  if (judges.empty() || gone == Gone::kRefuted || (need_proof && gone != Gone::kProved)) return 0;
  const auto judged_free = [this, &f, &judges](int px) {
    for (const FreeSpaceCheck::PastView& v : judges)
      if (surfaceNear(*proj_, free_space_, v, f.pointAt(px))) return false;
    return true;
  };
  seeds.erase(std::remove_if(seeds.begin(), seeds.end(),
                             [&judged_free](int px) { return !judged_free(px); }),
              seeds.end());
  if (seeds.size() < kMinFill) return 0;
  Cluster fill;
  fill.pixels = std::move(seeds);
  computeClusterShape(f, fill);
  // No wider than the object, but for the growth's step: a fill holds no one beside it.
  if ((fill.max - fill.min).head<2>().norm() > extent(o) + grower_.params().distance) return 0;
  // Porous (foliage, seen into and through) is not a mover either (§7b).
  if (free_space_.min_solid_ratio > 0 &&
      solidRatio(f, fill, free_space_) < free_space_.min_solid_ratio)
    return 0;
  TrackedObject t;
  t.id = o.id;
  t.dynamic = true;
  t.filled = true;
  t.age = std::max(0, o.age - static_cast<int>(held.size() - 1 - j));
  t.velocity = (T_jk.linear() * Eigen::Vector3d(o.velocity.x(), o.velocity.y(), 0)).head<2>();
  t.centroid = fill.centroid;
  t.box_min = fill.min;
  t.box_max = fill.max;
  const RegionGrower::Admit admit = [&judged_free, &later](std::size_t i, int px) {
    return judged_free(px) && (!later || later(i, px));
  };
  t.points = grower_.grow(f, r.ground, {fill.pixels}, r.dynamic, owner_, admit)[0];
  for (int px : fill.pixels) r.seeds(px / cols, px % cols) = 255;
  t.cluster = std::move(fill.pixels);
  r.objects.push_back(std::move(t));
  return r.objects.back().points;
}

std::vector<FreeSpaceCheck::PastView> Hindsight::judgesOf(const std::vector<Held>& held,
                                                          std::size_t j, double speed,
                                                          double clearance) const {
  std::vector<FreeSpaceCheck::PastView> views;
  // The nearest held frame on each side by which the object had moved `clearance` away.
  for (const int side : {+1, -1}) {
    Eigen::Isometry3d T_ji = Eigen::Isometry3d::Identity();  // frame i's coordinates into j's
    std::size_t i = j;
    while (side > 0 ? i + 1 < held.size() : i > 0) {
      if (side > 0) {
        T_ji = T_ji * held[++i].result->ego_motion.motion;
      } else {
        T_ji = T_ji * held[i].result->ego_motion.motion.inverse();
        --i;
      }
      const std::size_t a = std::min(i, j), b = std::max(i, j);
      if (speed * secondsBetween(held[a], held[b], b - a) <= clearance) continue;
      const cv::Mat_<std::uint8_t>& ground = held[i].result->ground;
      views.push_back({&held[i].frame->range,
                       ground.size() == held[i].frame->range.size() ? &ground : nullptr,
                       T_ji.inverse()});
      break;
    }
  }
  return views;
}

Hindsight::Gone Hindsight::verdict(const LidarFrame& f,
                                   const std::vector<FreeSpaceCheck::PastView>& views,
                                   const std::vector<int>& pixels) {
  const SphericalProjection& proj = projectionFor(f);  // one sensor: every held frame's
  bool proved = false;
  for (const FreeSpaceCheck::PastView& v : views) {
    std::size_t surface = 0, through = 0;
    for (int px : pixels) {
      const cv::Vec3f& p = f.pointAt(px);
      const Eigen::Vector3d q = v.T * Eigen::Vector3d(p[0], p[1], p[2]);
      int r = -1, c = -1;
      if (!proj.pixelOf(q.x(), q.y(), q.z(), r, c) || (*v.ranges)(r, c) <= 0) continue;
      const double seen = (*v.ranges)(r, c), tolerance = 0.5 * free_space_.tolerance(q.norm());
      if (seen > q.norm() + tolerance)
        through++;
      else if (seen >= q.norm() - tolerance && !(v.ground && (*v.ground)(r, c)))
        surface++;
    }
    if (2 * surface >= pixels.size()) return Gone::kRefuted;  // something stands there
    proved = proved || 2 * through >= pixels.size();
  }
  return proved ? Gone::kProved : Gone::kUnknown;
}

std::optional<Eigen::Vector3d> Hindsight::backAt(const std::vector<Held>& held, std::size_t j,
                                                 const TrackedObject& o) const {
  // From its earliest place met going back, at its speed out of there over speed_window (to the
  // newest sweep when none is that far on; the track's own when it was seen only now).
  const auto& [jb, pb] = path_.back();
  Eigen::Vector2d v = o.velocity;
  if (path_.size() > 1) {
    std::size_t to = 0;
    for (std::size_t i = path_.size() - 1; i-- > 0;)
      if (secondsBetween(held[jb], held[path_[i].first], path_[i].first - jb) >=
          p_.speed_window - 1e-9) {
        to = i;
        break;
      }
    const std::size_t j2 = path_[to].first;
    v = (path_[to].second - pb).head<2>() / secondsBetween(held[jb], held[j2], j2 - jb);
  }
  if (v.norm() < p_.min_speed) return std::nullopt;  // not moving then
  const double dt = secondsBetween(held[j], held[jb], jb - j);
  return Eigen::Vector3d(pb.x() - v.x() * dt, pb.y() - v.y() * dt, pb.z());
}

long Hindsight::fillGap(const std::vector<Held>& held, const TrackedObject& o) {
  const std::size_t k = held.size() - 1;
  Eigen::Isometry3d T_jk = Eigen::Isometry3d::Identity();
  std::vector<std::pair<std::size_t, Eigen::Isometry3d>> unseen;  // newest first
  for (std::size_t j = k; j-- > 0;) {
    T_jk = held[j + 1].result->ego_motion.motion * T_jk;
    const TrackedObject* seen = findTrack(held[j].result->objects, o.id);
    if (!seen) {
      unseen.emplace_back(j, T_jk);
      continue;
    }
    if (unseen.empty() || !seen->dynamic) return 0;
    // Between the two sightings, in the newest frame's coordinates: it moved, it did not jump.
    const Eigen::Vector3d from = T_jk.inverse() * seen->centroid;
    const double span = secondsBetween(held[j], held[k], k - j);
    if ((o.centroid - from).head<2>().norm() < p_.min_speed * span) return 0;
    long added = 0;
    for (const auto& [ju, T_uk] : unseen)
      added +=
          fillUnseen(held, ju, o,
                     from + secondsBetween(held[j], held[ju], ju - j) / span * (o.centroid - from),
                     T_uk, false);
    return added;
  }
  return 0;
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
    bool lost = false;     // fill_before found nothing in a sweep since the last sighting
    path_.clear();         // where the track was seen, in frame k's coordinates, newest first
    path_.emplace_back(k, o.centroid);
    for (std::size_t j = k; j-- > 0;) {
      T_jk = held[j + 1].result->ego_motion.motion * T_jk;
      DetectionResult& r = *held[j].result;
      TrackedObject* earlier = findTrack(r.objects, o.id);
      if (earlier && earlier->filled) continue;  // between two sightings (fill_gaps)
      if (!earlier) {  // not seen then (coasting, or before its first sighting)
        // fill_before: past the start of the run just trusted, the object at its speed then.
        if (!p_.fill_before || lost || !(revising || run == trusted || (last && run < trusted)))
          continue;
        const std::optional<Eigen::Vector3d> at = backAt(held, j, o);
        const int grown = at ? fillUnseen(held, j, o, *at, T_jk, true) : 0;
        if (grown == 0) {
          lost = true;  // until the track is seen again going back
          continue;
        }
        revising = true;
        added += grown;
        path_.emplace_back(j, T_jk.inverse() * r.objects.back().centroid);
        continue;
      }
      lost = false;
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
    if (p_.fill_gaps) added += fillGap(held, o);
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
  if (!p_.stop_check || held.size() < 2) return 0;
  const auto start = std::chrono::steady_clock::now();
  DetectionResult& first = *held[0].result;
  int unflagged = 0;
  for (TrackedObject& o : first.objects) {
    if (!o.dynamic) continue;
    // Where the track is in the later held frames that see it, carried into the first frame
    // (T_{0<-j}); no verdict across a failed ego-motion.
    Eigen::Isometry3d T_0j = Eigen::Isometry3d::Identity();
    path_.clear();  // the first frame and the later ones that see the track, oldest first
    path_.emplace_back(0, o.centroid);
    for (std::size_t j = 1; j < held.size(); j++) {
      const DetectionResult& r = *held[j].result;
      if (!r.ego_motion.ok) break;
      T_0j = T_0j * r.ego_motion.motion;
      const TrackedObject* later = findTrack(r.objects, o.id);
      if (!later) continue;
      path_.emplace_back(j, T_0j * later->centroid);
    }
    if (!stoppedAt(held, o)) continue;
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
