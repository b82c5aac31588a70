// SPDX-License-Identifier: BSD-3-Clause
// The types of the ego-motion stage (paper III-B-1, Eq. 5): its parameters and its result, shared
// by the estimator (EgoMotionEstimator), its solver (MotionFromMatches) and the detector's result.
#pragma once

#include <Eigen/Geometry>
#include <string>

#include "dynobj/core/Params.h"

namespace dynobj::core {

struct EgoMotionParams : public StageParams {
  int features = 400;                 ///< ORB nfeatures
  double scale_factor = 1.2;          ///< ORB scaleFactor
  int levels = 1;                     ///< ORB nlevels (the 33 px padding gives level 0 room)
  int fast_threshold = 10;            ///< ORB fastThreshold (10 suits sparse indoor scenes)
  double ratio = 0.8;                 ///< Lowe ratio test
  int match_window = 64;              ///< [columns] match only keypoints this close in azimuth
                                      ///< (0 = all); on failure, all are tried before giving up
  int border = 2;                     ///< [px] no keypoint this close to a no-return pixel (one
                                      ///< between returns above and below does not count)
  double inlier_distance = 0.10;      ///< [m] RANSAC inlier threshold at close range ...
  double inlier_range_factor = 0.01;  ///< ... plus this fraction of the point's range
  /// [px] beyond the paper: a keypoint's pixel is uncertain by this much in each image direction,
  /// and so its point by that much of the step to the neighbouring pixels on its surface: along a
  /// surface seen at a grazing angle (the ground, a facade ahead) that is metres. The inlier test
  /// and the fit weigh each match's residual by the inverse of that spread plus the isotropic
  /// threshold, so a keypoint that kept its pixel while the sensor slid along the surface does not
  /// vote for no motion (0 = the paper's isotropic test and closed-form fit)
  double pixel_spread = 1.0;
  /// [px] beyond the paper: a match that kept its pixel is no inlier of a motion that moves its
  /// point by more than this across or along the scan. Where a line runs along the direction of
  /// travel (a lane marking, a kerb, a facade's edge), its crossing with a scan ring or column is a
  /// corner that stays in its pixel however far the sensor goes: a 512-column estimate along a
  /// street voted for 14 % less motion than was travelled (0 = off)
  double still_match_pixels = 1.0;
  int iterations = 200;           ///< RANSAC iterations at most ...
  double confidence = 0.9999;     ///< ... fewer once an all-inlier sample was drawn with this
                                  ///< probability (1 = always all)
  int refinements = 3;            ///< least-squares refits, inliers re-selected each time
  int min_inliers = 25;           ///< fewer -> ego-motion failed
  double min_inlier_ratio = 0.3;  ///< inliers / matches below this -> failed
  int seed = 1;                   ///< RANSAC random seed

  void visit(ParamVisitor& v) override;
};

/// The motion between the previous frame and the current one.
struct EgoMotion {
  /// T_{prev<-cur}: maps points of the current frame into the previous frame (the robot's motion).
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  bool ok = false;  ///< estimated with enough inliers (or given externally)
  int matches = 0;  ///< ratio-test matches with 3D points on both sides
  int inliers = 0;
  bool refined = false;         ///< corrected by the geometric refinement (EgoMotionRefiner)
  std::string source = "none";  ///< "intensity", "geometric" (features failed, geometry held),
                                ///< "external", "constant-velocity", "none"
};

}  // namespace dynobj::core
