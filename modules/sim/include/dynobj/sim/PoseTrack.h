// SPDX-License-Identifier: BSD-3-Clause
// Planar motion of actors and of the sensor platform: a time-stamped list of key poses, linearly
// interpolated. Every trajectory kind of a scenario (waypoints, random walks, stop-and-go,
// stand-then-walk) is turned into one of these when the scenario is loaded, so motion is
// deterministic and cheap to query.
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

namespace dynobj::sim {

struct Pose2 {
  double x = 0, y = 0, yaw = 0;
};

class PoseTrack {
 public:
  struct Key {
    double t;  ///< [s] since the start of the sequence
    Pose2 pose;
  };

  PoseTrack() = default;
  /// Keys must have non-decreasing times (throws std::invalid_argument otherwise).
  explicit PoseTrack(std::vector<Key> keys);

  /// Pose at time t (held constant before the first / after the last key).
  Pose2 at(double t) const;
  /// Velocity [m/s] at time t: that of the segment containing t (0 while standing).
  Eigen::Vector2d velocity(double t) const;
  double speed(double t) const { return velocity(t).norm(); }
  const std::vector<Key>& keys() const { return keys_; }

  /// Standing still at `p` for ever.
  static PoseTrack stationary(const Pose2& p);
  /// Stands at pts[0] until `start`, then walks pts[0] -> pts[1] -> ... at `speed`, pausing
  /// `pause` seconds at each waypoint; `loop` returns to pts[0] and repeats, otherwise it stops at
  /// the last point. Keys are generated up to `duration`.
  static PoseTrack waypoints(const std::vector<Eigen::Vector2d>& pts, double speed, double pause,
                             bool loop, double start, double duration);
  /// Random walk inside [xmin, xmax] x [ymin, ymax] (region = {xmin, ymin, xmax, ymax}): from
  /// `from`, stand until `start`, then walk to random targets at a speed drawn in
  /// [speed_lo, speed_hi], pausing a time drawn in [pause_lo, pause_hi] at each.
  static PoseTrack randomWalk(const Eigen::Vector4d& region, const Eigen::Vector2d& from,
                              double speed_lo, double speed_hi, double pause_lo, double pause_hi,
                              double start, double duration, std::mt19937& rng);

 private:
  std::size_t segment(double t) const;
  std::vector<Key> keys_;
};

}  // namespace dynobj::sim
