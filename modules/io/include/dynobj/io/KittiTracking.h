// SPDX-License-Identifier: BSD-3-Clause
// KITTI tracking annotations (devkit_tracking, `label_02/<seq>.txt` and `calib/<seq>.txt`): human
// 3-D boxes with track ids, in the rectified camera-0 frame, and the calibration that maps a
// Velodyne point into that frame and onto the left colour image.
//   label row:  frame track_id type truncated occluded alpha x1 y1 x2 y2 h w l x y z ry [score]
//               (x, y, z) = bottom centre of the box [m], camera axes (x right, y down, z ahead);
//               ry = yaw about the camera's y axis; h, w, l = height, width, length [m].
//               `DontCare` rows (track_id -1) mark regions nobody annotated.
//   calib:      "P2: 12 numbers" (3x4), "R_rect 9" (3x3; or R0_rect), "Tr_velo_cam 12" (3x4; or
//               Tr_velo_to_cam), keys followed by ':' or not.
#pragma once

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace dynobj::io {

struct KittiBox {
  int frame = 0;
  int track_id = 0;  ///< -1 for DontCare
  std::string type;  ///< Car, Van, Truck, Pedestrian, Person_sitting, Cyclist, Tram, Misc, DontCare
  int truncated = 0, occluded = 0;
  double h = 0, w = 0, l = 0;       ///< [m]
  Eigen::Vector3d bottom{0, 0, 0};  ///< bottom centre, rectified camera-0 frame [m]
  double ry = 0;                    ///< [rad] yaw about the camera's y axis
};

/// Reads a KITTI tracking label file (rows in any frame order). Throws FormatError
/// "<path>:<line>: <problem>" for a short row or a non-numeric field.
std::vector<KittiBox> readKittiTrackingLabels(const std::string& path);

struct KittiCalib {
  Eigen::Matrix<double, 3, 4> P2 = Eigen::Matrix<double, 3, 4>::Zero();
  Eigen::Matrix3d R_rect = Eigen::Matrix3d::Identity();
  /// Velodyne -> camera 0 (unrectified).
  Eigen::Isometry3d velo_to_cam = Eigen::Isometry3d::Identity();

  /// Velodyne -> rectified camera 0: R_rect * Tr_velo_cam.
  Eigen::Isometry3d veloToRect() const;
};

/// Reads a KITTI calibration file (tracking layout, or the raw recordings' per-file layout with
/// "P_rect_02", "R_rect_00"). Throws FormatError naming the missing key.
KittiCalib readKittiCalib(const std::string& path);

}  // namespace dynobj::io
