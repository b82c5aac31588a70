// SPDX-License-Identifier: BSD-3-Clause
// Internal: MRPT poses <-> Eigen isometries (the module's MRPT-facing files only).
#pragma once

#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/poses/CPose3D.h>

#include <Eigen/Geometry>

namespace dynobj::mapclean::detail {

inline Eigen::Isometry3d toIsometry(const ::mrpt::poses::CPose3D& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.matrix() = p.getHomogeneousMatrixVal<::mrpt::math::CMatrixDouble44>().asEigen();
  return T;
}

inline ::mrpt::poses::CPose3D toCPose3D(const Eigen::Isometry3d& T) {
  ::mrpt::math::CMatrixDouble44 m;
  m.asEigen() = T.matrix();
  return ::mrpt::poses::CPose3D(m);
}

}  // namespace dynobj::mapclean::detail
