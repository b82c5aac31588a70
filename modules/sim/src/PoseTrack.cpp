// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/PoseTrack.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynobj::sim {
namespace {

double wrapAngle(double a) {
  return std::atan2(std::sin(a), std::cos(a));
}

/// Appends a walk from the last key to `to` at `speed`, then a pause.
void walkTo(std::vector<PoseTrack::Key>& keys, const Eigen::Vector2d& to, double speed,
            double pause) {
  const PoseTrack::Key last = keys.back();
  const Eigen::Vector2d from(last.pose.x, last.pose.y);
  const double dist = (to - from).norm();
  if (dist < 1e-6 || speed <= 0) return;
  const double yaw = std::atan2(to.y() - from.y(), to.x() - from.x());
  keys.push_back({last.t, {from.x(), from.y(), yaw}});  // turn in place
  keys.push_back({last.t + dist / speed, {to.x(), to.y(), yaw}});
  if (pause > 0) keys.push_back({keys.back().t + pause, keys.back().pose});
}

}  // namespace

PoseTrack::PoseTrack(std::vector<Key> keys) : keys_(std::move(keys)) {
  for (std::size_t i = 1; i < keys_.size(); i++)
    if (keys_[i].t < keys_[i - 1].t) throw std::invalid_argument("PoseTrack: key times decrease");
}

std::size_t PoseTrack::segment(double t) const {
  // Last key with time <= t (keys may share a time: take the last of them).
  const auto it = std::upper_bound(keys_.begin(), keys_.end(), t,
                                   [](double v, const Key& k) { return v < k.t; });
  return it == keys_.begin() ? 0 : static_cast<std::size_t>(it - keys_.begin()) - 1;
}

Pose2 PoseTrack::at(double t) const {
  if (keys_.empty()) return {};
  if (t <= keys_.front().t) return keys_.front().pose;
  if (t >= keys_.back().t) return keys_.back().pose;
  const std::size_t i = segment(t);
  const Key& a = keys_[i];
  const Key& b = keys_[i + 1];
  const double span = b.t - a.t;
  const double s = span > 0 ? (t - a.t) / span : 1.0;
  return {a.pose.x + s * (b.pose.x - a.pose.x), a.pose.y + s * (b.pose.y - a.pose.y),
          wrapAngle(a.pose.yaw + s * wrapAngle(b.pose.yaw - a.pose.yaw))};
}

Eigen::Vector2d PoseTrack::velocity(double t) const {
  if (keys_.size() < 2 || t < keys_.front().t || t >= keys_.back().t) return {0, 0};
  const std::size_t i = segment(t);
  const Key& a = keys_[i];
  const Key& b = keys_[i + 1];
  const double span = b.t - a.t;
  if (span <= 0) return {0, 0};
  return {(b.pose.x - a.pose.x) / span, (b.pose.y - a.pose.y) / span};
}

PoseTrack PoseTrack::stationary(const Pose2& p) {
  return PoseTrack({{0.0, p}});
}

PoseTrack PoseTrack::waypoints(const std::vector<Eigen::Vector2d>& pts, double speed, double pause,
                               bool loop, double start, double duration) {
  if (pts.empty()) throw std::invalid_argument("waypoints: no points");
  if (pts.size() > 1 && !(speed > 0)) throw std::invalid_argument("waypoints: speed must be > 0");
  double yaw0 = 0;
  if (pts.size() > 1) yaw0 = std::atan2(pts[1].y() - pts[0].y(), pts[1].x() - pts[0].x());
  std::vector<Key> keys{{0.0, {pts[0].x(), pts[0].y(), yaw0}}};
  if (start > 0) keys.push_back({start, keys.back().pose});
  if (pts.size() == 1) return PoseTrack(std::move(keys));
  std::size_t next = 1;
  while (keys.back().t < duration) {
    walkTo(keys, pts[next], speed, pause);
    if (++next == pts.size()) {
      if (!loop) break;
      next = 0;
    }
  }
  return PoseTrack(std::move(keys));
}

PoseTrack PoseTrack::randomWalk(const Eigen::Vector4d& region, const Eigen::Vector2d& from,
                                double speed_lo, double speed_hi, double pause_lo, double pause_hi,
                                double start, double duration, std::mt19937& rng) {
  if (!(region[2] > region[0] && region[3] > region[1]))
    throw std::invalid_argument("random_walk: empty region");
  if (!(speed_lo > 0 && speed_hi >= speed_lo))
    throw std::invalid_argument("random_walk: need 0 < speed_lo <= speed_hi");
  std::uniform_real_distribution<double> ux(region[0], region[2]), uy(region[1], region[3]);
  std::uniform_real_distribution<double> us(speed_lo, speed_hi),
      up(pause_lo, std::max(pause_lo, pause_hi));
  std::vector<Key> keys{{0.0, {from.x(), from.y(), 0.0}}};
  if (start > 0) keys.push_back({start, keys.back().pose});
  while (keys.back().t < duration) {
    Eigen::Vector2d target(ux(rng), uy(rng));
    for (int tries = 0;
         tries < 10 &&
         (target - Eigen::Vector2d(keys.back().pose.x, keys.back().pose.y)).norm() < 2.0;
         tries++)
      target = Eigen::Vector2d(ux(rng), uy(rng));
    const double speed = us(rng), pause = up(rng);
    const std::size_t before = keys.size();
    walkTo(keys, target, speed, pause);
    if (keys.size() == before) keys.push_back({keys.back().t + 1.0, keys.back().pose});
  }
  return PoseTrack(std::move(keys));
}

}  // namespace dynobj::sim
