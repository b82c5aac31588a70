// SPDX-License-Identifier: BSD-3-Clause
// Drifting odometry for the robustness baseline: true frame-to-frame motions corrupted by
// per-frame noise and a slow bias (a scale error and a yaw rate), so that the accumulated pose
// drifts without bound while each short window stays nearly right.
#pragma once

#include <Eigen/Geometry>
#include <random>
#include <string>

namespace dynobj::eval {

struct DriftParams {
  double sigma_xy = 0.005;      ///< [m] per-frame translation noise (each axis)
  double sigma_yaw_deg = 0.05;  ///< [deg] per-frame yaw noise
  double bias_scale = 0.05;     ///< translation scale error (0.05 = 5 % too long)
  double bias_yaw_deg = 0.1;    ///< [deg] yaw bias added every frame (30 deg over 300 frames)
  int seed = 1;

  /// "sigma_xy=0.05,bias_yaw_deg=0.1": unknown keys or bad numbers throw std::invalid_argument.
  static DriftParams parse(const std::string& text);
  std::string toString() const;
};

class DriftModel {
 public:
  explicit DriftModel(const DriftParams& p = {});
  /// The corrupted version of one true motion T_{prev<-cur} (sensor frame, z up).
  Eigen::Isometry3d corrupt(const Eigen::Isometry3d& motion);

 private:
  DriftParams p_;
  std::mt19937 rng_;
};

}  // namespace dynobj::eval
