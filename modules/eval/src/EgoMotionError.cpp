// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/EgoMotionError.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace dynobj::eval {

void EgoMotionError::add(const Eigen::Isometry3d& truth, const Eigen::Isometry3d& estimate) {
  const Eigen::Isometry3d e = truth.inverse() * estimate;
  const double t = e.translation().norm();
  const double r = Eigen::AngleAxisd(e.linear()).angle() * 180.0 / M_PI;
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
