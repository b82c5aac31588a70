// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/FreeSpaceCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "dynobj/core/Config.h"

namespace dynobj::core {

void FreeSpaceParams::visit(ParamVisitor& v) {
  v.value("enabled", enabled);
  v.value("margin", margin, kPositive);
  v.value("range_factor", range_factor, {0, 1});
  v.value("min_free_ratio", min_free_ratio, {0, 1});
  v.value("min_evidence", min_evidence, {0, 1000000});
  v.value("require_proof", require_proof);
  v.value("lookback", lookback, {1, 1000});
  v.value("max_lookback", max_lookback, {0, 1000});
  v.value("clear_tolerances", clear_tolerances, {0, 100});
  v.value("max_travel", max_travel, kPositive);
  v.value("side_rays", side_rays, {0, 100});
  v.value("side_rows", side_rows, {0, 100});
  v.value("min_solid_ratio", min_solid_ratio, {0, 1});
  v.value("slide_free_ratio", slide_free_ratio, {0, 1});
  v.value("clearance", clearance, {0, 100});
  v.value("release_free_ratio", release_free_ratio, {0, 1});
  v.value("exclude_own_past", exclude_own_past);
  v.value("thin_frames", thin_frames, {0, 10});
}

namespace {
double freeRatioNeeded(const FreeSpaceParams& p, bool slides) {
  return slides ? std::max(p.min_free_ratio, p.slide_free_ratio) : p.min_free_ratio;
}
}  // namespace

bool FreeSpaceEvidence::supportsMotion(const FreeSpaceParams& p, bool slides) const {
  const int decisive = free + occupied;
  if (decisive < p.min_evidence) return true;  // no verdict: keep the candidate
  return free >= freeRatioNeeded(p, slides) * decisive;
}

bool FreeSpaceEvidence::provesMotion(const FreeSpaceParams& p, bool slides) const {
  const int decisive = free + occupied;
  return decisive >= p.min_evidence && free >= freeRatioNeeded(p, slides) * decisive;
}

FreeSpaceCheck::FreeSpaceCheck(const FreeSpaceParams& p, std::size_t history)
    : p_(p), history_(std::max<std::size_t>(history, 2)) {
  p_.validate();
}

void FreeSpaceCheck::remember(long index, const LidarFrame& frame,
                              const cv::Mat_<std::uint8_t>& ground) {
  if (!p_.enabled) return;
  if (!proj_ || proj_->sensor().rows != frame.rows() || proj_->sensor().cols != frame.cols())
    proj_.emplace(frame.sensor);     // built once, not per candidate
  if (frames_.size() >= history_) {  // recycle the oldest buffers
    Remembered oldest = std::move(frames_.front());
    frames_.pop_front();
    oldest.index = index;
    frame.range.copyTo(oldest.range);
    ground.copyTo(oldest.ground);
    frames_.push_back(std::move(oldest));
    return;
  }
  frames_.push_back({index, frame.range.clone(), ground.clone()});
}

namespace {

/// One ray test: `seen` is the range measured along the ray through a point expected at range
/// `expected`.
void tally(FreeSpaceEvidence& e, double seen, double expected, double tol) {
  if (seen <= 0)
    e.unknown++;  // no return
  else if (seen > expected + tol)
    e.free++;  // the ray went through: free space
  else if (seen >= expected - tol)
    e.occupied++;  // a surface is there
  else
    e.unknown++;  // something nearer hid it
}

}  // namespace

bool FreeSpaceCheck::sawSurface(const cv::Mat_<float>& seen, const Eigen::Vector3d& q,
                                double tolerance_scale,
                                const cv::Mat_<std::uint8_t>* ground) const {
  return surfaceAt(*proj_, seen, ground, q, tolerance_scale * p_.tolerance(q.norm()));
}

bool FreeSpaceCheck::surfaceAt(const SphericalProjection& proj, const cv::Mat_<float>& seen,
                               const cv::Mat_<std::uint8_t>* ground, const Eigen::Vector3d& q,
                               double tolerance) {
  int r = -1, c = -1;
  if (!proj.pixelOf(q.x(), q.y(), q.z(), r, c)) return false;
  if (ground && (*ground)(r, c)) return false;
  return std::abs(seen(r, c) - q.norm()) <= tolerance;
}

double FreeSpaceCheck::rayBeside(const cv::Mat_<float>& seen, int r, int c, double through,
                                 double height, const cv::Mat_<std::uint8_t>* ground) const {
  const double own = seen(r, c);
  if (own <= through) return own;  // it did not go through: its own ray decides
  const int W = seen.cols;
  double nearest = own;
  auto consider = [&](int rr, int cc) {
    const float n = seen(rr, cc);
    if (n <= 0) return;
    // The ground under a point well above it (a car's bumper) is not the point's surface.
    if (ground && (*ground)(rr, cc) && height - n * proj_->sinElevationOfRow(rr) > p_.clearance)
      return;
    nearest = std::min<double>(nearest, n);
  };
  for (int dc = -p_.side_rays; dc <= p_.side_rays; ++dc) consider(r, ((c + dc) % W + W) % W);
  for (int dr = 1; dr <= p_.side_rows; ++dr)
    for (const int rr : {r - dr, r + dr})
      if (rr >= 0 && rr < seen.rows) consider(rr, c);
  return nearest;
}

bool FreeSpaceCheck::resolved(const LidarFrame& frame, int px) const {
  const int W = frame.cols(), H = frame.rows(), r = px / W, c = px % W;
  const float range = frame.range(r, c);
  const double tol = p_.tolerance(range);
  const auto agrees = [&](int rr, int cc) {
    const float n = frame.range(rr, (cc + W) % W);
    return n > 0 && std::abs(n - range) <= tol;
  };
  return (agrees(r, c - 1) || agrees(r, c + 1)) &&
         ((r > 0 && agrees(r - 1, c)) || (r + 1 < H && agrees(r + 1, c)));
}

double solidRatio(const LidarFrame& frame, const Cluster& cluster, const FreeSpaceParams& p) {
  const int H = frame.rows(), W = frame.cols();
  // Fewer than 3 columns wide (a far person): every pixel is on the outline, none inside.
  int columns[2] = {-1, -1}, distinct = 0;
  for (int px : cluster.pixels) {
    const int c = px % W;
    if (c == columns[0] || c == columns[1]) continue;
    if (distinct == 2) {
      distinct = 3;
      break;
    }
    columns[distinct++] = c;
  }
  if (distinct < 3) return 1.0;
  int pixels = 0, solid = 0;
  for (int px : cluster.pixels) {
    const int r = px / W, c = px % W;
    const float range = frame.range(r, c);
    if (range <= 0) continue;
    const double tol = p.tolerance(range);
    int valid = 0, agree = 0;
    for (int dr = -1; dr <= 1; ++dr) {
      const int rr = r + dr;
      if (rr < 0 || rr >= H) continue;
      for (int dc = -1; dc <= 1; ++dc) {
        if (dr == 0 && dc == 0) continue;
        const float n = frame.range(rr, (c + dc + W) % W);
        if (n <= 0) continue;
        valid++;
        if (std::abs(n - range) <= tol) agree++;
      }
    }
    pixels++;
    if (valid > 0 && 2 * agree >= valid) solid++;
  }
  return pixels > 0 ? static_cast<double>(solid) / pixels : 1.0;
}

std::optional<FreeSpaceCheck::PastView> FreeSpaceCheck::pastView(const LidarFrame& frame,
                                                                 long current, long past,
                                                                 const FrameChain& chain) const {
  for (const Remembered& m : frames_) {
    if (m.index != past) continue;
    if (!p_.enabled || !proj_ || !chain.contains(past) || !chain.contains(current) ||
        m.range.size() != frame.range.size())
      return std::nullopt;
    const cv::Mat_<std::uint8_t>& g = m.ground;
    return PastView{&m.range, g.size() == frame.range.size() ? &g : nullptr,
                    chain.between(past, current)};
  }
  return std::nullopt;
}

bool FreeSpaceCheck::sawSurfaceIn(const SphericalProjection& proj, const FreeSpaceParams& params,
                                  const PastView& view, const cv::Vec3f& p) {
  const Eigen::Vector3d q = view.T * Eigen::Vector3d(p[0], p[1], p[2]);
  return surfaceAt(proj, *view.ranges, view.ground, q, 0.5 * params.tolerance(q.norm()));
}

FreeSpaceEvidence FreeSpaceCheck::evidence(const LidarFrame& frame, long current,
                                           const Cluster& cluster, long past,
                                           const FrameChain& chain,
                                           const std::optional<Eigen::Vector3d>& shift,
                                           const cv::Mat_<std::uint8_t>& ground,
                                           bool own_past) const {
  FreeSpaceEvidence e;
  const std::optional<PastView> view = pastView(frame, current, past, chain);
  if (!view) return e;
  const cv::Mat_<float>* old = view->ranges;
  const Eigen::Isometry3d& T = view->T;  // current -> past frame
  // Where its own body was then (own_past): less than its travel behind its front, along its
  // motion. Those points are unknown in the test against the past frame.
  const double travel = shift && own_past ? shift->head<2>().norm() : 0.0;
  const Eigen::Vector2d along =
      travel > 0 ? Eigen::Vector2d(shift->head<2>() / travel) : Eigen::Vector2d::Zero();
  double front = -std::numeric_limits<double>::infinity();
  if (travel > 0)
    for (int px : cluster.pixels) {
      const cv::Vec3f& p = frame.pointAt(px);
      front = std::max(front, along.x() * p[0] + along.y() * p[1]);
    }
  const auto ownPast = [&](const cv::Vec3f& p) {
    return travel > 0 && along.x() * p[0] + along.y() * p[1] + travel <= front + p_.margin;
  };
  // One ray test of a point `q` placed in the frame of the range image `seen`.
  const auto rayTest = [&](const Eigen::Vector3d& q, const cv::Mat_<float>& seen,
                           const cv::Mat_<std::uint8_t>* seen_ground) {
    FreeSpaceEvidence one;
    int r = -1, c = -1;
    if (!proj_->pixelOf(q.x(), q.y(), q.z(), r, c)) {
      one.unknown++;
      return one;
    }
    const double expected = q.norm(), tol = p_.tolerance(expected);
    tally(one, rayBeside(seen, r, c, expected + tol, q.z(), seen_ground), expected, tol);
    return one;
  };
  // The frames beside the past one (thin_frames), gathered at the first point that needs them.
  std::vector<PastView> beside;
  bool gathered = false;
  for (int px : cluster.pixels) {
    const cv::Vec3f& p = frame.pointAt(px);
    if (ownPast(p)) {
      e.unknown++;
      continue;
    }
    const Eigen::Vector3d q(p[0], p[1], p[2]);
    const FreeSpaceEvidence then = rayTest(T * q, *old, view->ground);
    bool free = then.free > 0;
    // A point whose surface the rays do not resolve, seen through then, is free only where the
    // frames beside saw through it too; where one of them met it (a bar the past frame's rays
    // fell beside), it is no evidence either way.
    if (free && p_.thin_frames > 0 && !resolved(frame, px)) {
      if (!gathered) {
        gathered = true;
        for (long k = 1; k <= p_.thin_frames; ++k)
          for (const long other : {past - k, past + k})
            if (other < current)
              if (const auto v = pastView(frame, current, other, chain)) beside.push_back(*v);
      }
      for (const PastView& v : beside)
        if (rayTest(v.T * q, *v.ranges, v.ground).free == 0) {
          free = false;
          break;
        }
    }
    if (then.occupied > 0)
      e.occupied++;
    else if (free)
      e.free++;
    else
      e.unknown++;
  }
  if (!shift || e.free + e.occupied >= p_.min_evidence) return e;
  // No verdict (hidden then): the space it left, moved back by `shift`. Still occupied now
  // refutes the motion. Seen through now proves it only where the old frame saw a surface there
  // (the object itself): the space in front of a static object that only seems to recede, as it
  // comes out from behind an occluder, is seen through too.
  const bool ground_now = ground.size() == frame.range.size();
  for (int px : cluster.pixels) {
    const cv::Vec3f& p = frame.pointAt(px);
    const Eigen::Vector3d left = Eigen::Vector3d(p[0], p[1], p[2]) - *shift;
    FreeSpaceEvidence one = rayTest(left, frame.range, ground_now ? &ground : nullptr);
    if (one.free > 0 && !sawSurface(*old, T * left)) one = {0, 0, 1};
    e.free += one.free;
    e.occupied += one.occupied;
    e.unknown += one.unknown;
  }
  return e;
}

long FreeSpaceCheck::lookbackFor(const Cluster& cluster, const MovementDecision& d,
                                 const FrameChain& chain, long current, double dt) const {
  const double speed = d.velocity.head<2>().norm();
  if (p_.max_lookback <= p_.lookback || p_.clear_tolerances <= 0 || speed <= 0 || dt <= 0)
    return p_.lookback;
  // Far enough back that the candidate has moved clear_tolerances x the range tolerance: a
  // walker 20 m away moves 1 m in a second, barely more than the 0.7 m its ranges agree within.
  const double need = p_.clear_tolerances * p_.tolerance(cluster.centroid.norm());
  long k = static_cast<long>(
      std::clamp<double>(std::ceil(need / (speed * dt)), p_.lookback, p_.max_lookback));
  // ... from a frame the chain still holds, and not from farther than max_travel away: from
  // there, thin and grazing surfaces fall between the rays and look seen through.
  const long held = chain.contains(current) ? current - chain.oldest() : 0;
  while (k > p_.lookback &&
         (k > held || chain.between(current - k, current).translation().norm() > p_.max_travel))
    k--;
  return k;
}

void FreeSpaceCheck::review(const LidarFrame& frame, long current, const Cluster& cluster,
                            const FrameChain& chain, double dt, MovementDecision& d,
                            const cv::Mat_<std::uint8_t>& ground) const {
  if (!d.moving() || !p_.enabled) return;  // off: the paper's movement decision stands
  const bool must_prove = p_.require_proof || d.rigid || d.early;
  bool clearly = true;  // every frame tried saw hardly any of its space free
  auto refuted = [&](long back) {
    const long past = std::max(chain.oldest(), current - back);
    const Eigen::Vector3d shift = d.velocity * dt * static_cast<double>(current - past);
    const FreeSpaceEvidence e = evidence(frame, current, cluster, past, chain, shift, ground,
                                         p_.exclude_own_past && d.rigid);
    const int decisive = e.free + e.occupied;
    clearly = clearly && decisive >= p_.min_evidence && e.free < p_.release_free_ratio * decisive;
    return must_prove ? !e.provesMotion(p_, d.slides) : !e.supportsMotion(p_, d.slides);
  };
  // A slow candidate refuted by the usual frame may still prove its motion against an older one
  // (lookbackFor): its own earlier place may lie within the usual frame's tolerance. Only a
  // refuted candidate asks which frame that is.
  d.static_surface = refuted(p_.lookback);
  if (d.static_surface) {
    const long back = lookbackFor(cluster, d, chain, current, dt);
    if (back != p_.lookback) d.static_surface = refuted(back);
  }
  d.refuted = d.static_surface && clearly;
  // Seen through: only asked of a candidate the evidence above left standing.
  d.porous = !d.static_surface && p_.min_solid_ratio > 0 &&
             solidRatio(frame, cluster, p_) < p_.min_solid_ratio;
}

}  // namespace dynobj::core
