// SPDX-License-Identifier: BSD-3-Clause
// The project's one conversion between MRPT poses and Eigen isometries (same 4x4 matrix).
#pragma once

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Geometry>

namespace dynobj::mrptio {

inline Eigen::Isometry3d toIsometry(const mrpt::poses::CPose3D& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.matrix() = p.getHomogeneousMatrixVal<mrpt::math::CMatrixDouble44>().asEigen();
  return T;
}

inline mrpt::poses::CPose3D toCPose3D(const Eigen::Isometry3d& T) {
  mrpt::math::CMatrixDouble44 m;
  m.asEigen() = T.matrix();
  return mrpt::poses::CPose3D(m);
}

}  // namespace dynobj::mrptio
