// SPDX-License-Identifier: BSD-3-Clause
// Levels the sensor poses with the floor seen in each scan. Planar pose sources (wheel / legged
// odometry, 2D SLAM such as icp-slam) give x, y, yaw only, and chained ego-motion drifts in
// height, roll and pitch: a legged robot's bobbing then tilts whole scans, and the floor of the
// map becomes a slab tens of centimetres thick that swallows the people's feet and legs. The
// leveler fits a plane to the scan's ground pixels (core::GroundSegmenter, then least squares with
// one inlier refit) and replaces the pose's roll, pitch and height by the ones that put that
// plane level at the floor height of the first scan; x, y and yaw are kept.
// Assumes a level floor around the sensor (indoor, flat ground); off by default for that reason.
#pragma once

#include <dynobj/core/GroundSegmenter.h>
#include <dynobj/core/LidarFrame.h>

#include <Eigen/Geometry>
#include <optional>

namespace dynobj::mapclean {

/// A plane in the sensor frame: normal . p = -distance, normal pointing up (towards the sensor).
struct GroundPlane {
  Eigen::Vector3d normal{0, 0, 1};
  double distance = 0;  ///< [m] of the sensor above the plane
  std::size_t inliers = 0;
};

class GroundLeveler {
 public:
  /// `max_range` [m]: ground returns farther than this are not used (fit quality);
  /// `min_points`: fewer inliers leave the pose as it is.
  explicit GroundLeveler(double max_range = 15.0, std::size_t min_points = 200);

  /// Plane of the ground pixels of `frame`, or none when too few.
  std::optional<GroundPlane> fit(const core::LidarFrame& frame);

  /// `pose` with roll, pitch and height replaced so that `plane` is horizontal at the floor
  /// height (fixed by the first leveled scan: its height is kept). x, y, yaw are kept.
  Eigen::Isometry3d level(const Eigen::Isometry3d& pose, const GroundPlane& plane);

 private:
  double max_range_;
  std::size_t min_points_;
  core::GroundSegmenter segmenter_;
  cv::Mat_<std::uint8_t> ground_;
  std::optional<double> floor_z_;
};

}  // namespace dynobj::mapclean
