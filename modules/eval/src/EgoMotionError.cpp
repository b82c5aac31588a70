// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/EgoMotionError.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dynobj::eval {

MotionDifference motionDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d d = a.inverse() * b;
  return {d.translation().norm(), Eigen::AngleAxisd(d.linear()).angle() * 180.0 / M_PI};
}

void EgoMotionError::add(const Eigen::Isometry3d& truth, const Eigen::Isometry3d& estimate) {
  const auto [t, r] = motionDifference(truth, estimate);
  n_++;
  sum_t2_ += t * t;
  sum_r2_ += r * r;
  max_t_ = std::max(max_t_, t);
  max_r_ = std::max(max_r_, r);
}

double EgoMotionError::rmsTranslation() const {
  return n_ ? std::sqrt(sum_t2_ / static_cast<double>(n_)) : 0.0;
}

double EgoMotionError::rmsRotation() const {
  return n_ ? std::sqrt(sum_r2_ / static_cast<double>(n_)) : 0.0;
}

std::string EgoMotionError::toString() const {
  char buf[200];
  std::snprintf(buf, sizeof(buf),
                "ego-motion error over %zu pairs: translation RMS %.3f m (max %.3f), rotation RMS "
                "%.3f deg (max %.3f)",
                n_, rmsTranslation(), max_t_, rmsRotation(), max_r_);
  return buf;
}

}  // namespace dynobj::eval
