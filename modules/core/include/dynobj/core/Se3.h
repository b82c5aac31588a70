// SPDX-License-Identifier: BSD-3-Clause
// The one SE(3) increment of the Gauss-Newton steps (EgoMotionRefiner, motionFromMatches).
#pragma once

#include <Eigen/Geometry>

namespace dynobj::core {

/// The increment xi = (omega, v) as a transform: rotation exp(omega) (axis-angle), translation v
/// (first-order; applied on the left, T <- expSE3(xi) * T).
inline Eigen::Isometry3d expSE3(const Eigen::Matrix<double, 6, 1>& xi) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d w = xi.head<3>();
  const double a = w.norm();
  if (a > 1e-12) T.linear() = Eigen::AngleAxisd(a, w / a).toRotationMatrix();
  T.translation() = xi.tail<3>();
  return T;
}

}  // namespace dynobj::core
