// SPDX-License-Identifier: BSD-3-Clause
// Spinning-LiDAR ray caster over a Scenario: one organized sweep at a time, with range noise,
// dropouts, Ouster-like intensity and per-pixel ground truth (which actor each pixel hit).
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/PointCloud.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "dynobj/sim/Scenario.h"

namespace dynobj::sim {

struct ActorState {
  int id = 0;
  ActorClass cls = ActorClass::Pedestrian;
  Eigen::Vector3d position;  ///< world, centre of the body at half height [m]
  Eigen::Vector2d velocity;  ///< world [m/s]
  bool moving = false;       ///< speed > Scenario::moving_speed
  int points = 0;            ///< pixels of this sweep that hit it
};

struct SimulatedSweep {
  int index = 0;
  double t = 0;                    ///< [s] since the start of the sequence
  std::int64_t timestamp_ns = 0;   ///< Unix time
  core::LidarFrame frame;          ///< points in the sensor frame at their firing time
  cv::Mat_<std::int16_t> actor;    ///< actor id hit by each pixel, -1 = static scene / none
  cv::Mat_<std::uint8_t> dynamic;  ///< 255 where the pixel hit a moving actor (ground truth)
  Eigen::Isometry3d robot_pose;    ///< world pose of the robot at t
  Eigen::Isometry3d sensor_pose;   ///< world pose of the sensor at t
  std::vector<ActorState> actors;
};

class LidarSimulator {
 public:
  explicit LidarSimulator(Scenario scenario);

  const Scenario& scenario() const { return s_; }
  /// Simulates sweep `index` (0-based). Deterministic: the same scenario and index always give the
  /// same sweep, whatever was simulated before.
  SimulatedSweep simulate(int index) const;

  Eigen::Isometry3d robotPose(double t) const;
  Eigen::Isometry3d sensorPose(double t) const;
  std::int64_t timestampNs(int index) const;

 private:
  struct Posed;  // a part in world coordinates
  void poseWorld(double t, std::vector<Posed>& out) const;
  /// Pixels of a sweep with no return whatever they face (Realism: lost packets, runs of
  /// dropouts along a row), 255 = lost; empty when neither trait is on.
  cv::Mat_<std::uint8_t> lostPixels(std::uint64_t sweep_key) const;
  /// Mixed returns where a beam's footprint straddles a depth edge (Realism::beam_divergence)
  /// and interstitial points between the two surfaces (Realism::interstitial):
  /// moves points, their intensity and their ground truth (`actor`, `moving`, per point).
  void mixEdges(core::PointCloud& cloud, std::vector<std::int16_t>& actor,
                std::vector<std::uint8_t>& moving, std::uint64_t sweep_key) const;

  Scenario s_;
  std::vector<double> row_elev_;
};

}  // namespace dynobj::sim
