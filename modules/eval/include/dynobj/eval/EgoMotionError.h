// SPDX-License-Identifier: BSD-3-Clause
// The detector's ego-motion against known poses (a simulator's ground truth, a reference SLAM
// trajectory): per frame pair, the difference between the true motion T_{prev<-cur} and the
// estimate. What `dynobj-detect --ego-truth poses.tum` prints (docs/accuracy.md).
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <string>

namespace dynobj::eval {

/// How far apart two motions are: b expressed relative to a.
struct MotionDifference {
  double translation = 0;  ///< [m]
  double rotation = 0;     ///< [deg]
};
MotionDifference motionDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b);

class EgoMotionError {
 public:
  /// One frame pair: the true motion and the estimated one (both T_{prev<-cur}).
  void add(const Eigen::Isometry3d& truth, const Eigen::Isometry3d& estimate);

  std::size_t pairs() const { return n_; }
  double rmsTranslation() const;                    ///< [m]
  double rmsRotation() const;                       ///< [deg]
  double maxTranslation() const { return max_t_; }  ///< [m]
  double maxRotation() const { return max_r_; }     ///< [deg]
  /// "ego-motion error over N pairs: translation RMS a m (max b), rotation RMS c deg (max d)".
  std::string toString() const;

 private:
  std::size_t n_ = 0;
  double sum_t2_ = 0, sum_r2_ = 0, max_t_ = 0, max_r_ = 0;
};

}  // namespace dynobj::eval
