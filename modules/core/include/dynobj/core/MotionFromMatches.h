// SPDX-License-Identifier: BSD-3-Clause
// Paper III-B-1, Eq. (5), its solver: the rigid motion that maps the current frame's matched 3D
// points onto the previous frame's, by RANSAC over 3-point samples and least squares on the
// inliers. Beyond the paper (docs/algorithm.md §3): each match's residual is weighed by its pixel
// spread (pixel_spread), and a match that kept its pixel is no inlier of a motion that would have
// moved it (still_match_pixels).
#pragma once

#include <Eigen/Geometry>
#include <random>
#include <vector>

#include "dynobj/core/EgoMotion.h"

namespace dynobj::core {

/// One ORB match lifted to 3D.
struct PointMatch {
  Eigen::Vector3d cur = Eigen::Vector3d::Zero();   ///< [m] point in the current frame
  Eigen::Vector3d prev = Eigen::Vector3d::Zero();  ///< [m] its match in the previous frame
  /// [m^2] the two points' pixel spreads summed (EgoMotionEstimator: J_u J_u^T + J_v J_v^T)
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  bool still = false;  ///< both keypoints lie in the same pixel
};

/// [rad] angle between adjacent columns and adjacent rows (row = 0: no still-match test).
struct PixelPitch {
  double column = 0;
  double row = 0;
};

/// T_{prev<-cur} from `matches` (ok, matches, inliers and source "intensity" filled in); `rng`
/// draws the RANSAC samples.
EgoMotion motionFromMatches(const std::vector<PointMatch>& matches, const EgoMotionParams& p,
                            const PixelPitch& pitch, std::mt19937& rng);

}  // namespace dynobj::core
