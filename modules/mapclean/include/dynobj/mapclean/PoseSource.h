// SPDX-License-Identifier: BSD-3-Clause
// Where each scan is placed in the world (the sensor pose). Chosen by a spec string:
//   "auto"            - by the first scan: "odometry" when the rawlog has odometry before it, else
//                       "viewpoint" when it has a VIEWPOINT (PCD folders), else "ego"; describe()
//                       says which, and why;
//   "odometry"        - the rawlog's latest CObservationOdometry before the scan, composed with the
//                       observation's sensor pose on the robot;
//   "ego"             - the detector's own ego-motion, chained from the first scan (robot origin);
//   "viewpoint"       - the PCD input's VIEWPOINT (KTH DynamicMap folders);
//   "<file>.tum|.txt" - a TUM trajectory, matched by timestamp (sensor poses, or robot poses with
//                       tum_robot_poses, then composed with the mount);
//   "<file>.simplemap[.gz]" - keyframe robot poses of an MRPT simplemap (e.g. icp-slam's output),
//                       matched by observation timestamp; scans between keyframes are placed by the
//                       odometry increment since the last keyframe.
// Errors name the file, and the scan (index, time) that has no pose.
#pragma once

#include <dynobj/core/EgoMotionEstimator.h>

#include <Eigen/Geometry>
#include <memory>
#include <string>

#include "dynobj/mapclean/ScanSource.h"

namespace dynobj::mapclean {

struct PoseSourceOptions {
  double tolerance_s = 0.001;    ///< timestamp matching tolerance for TUM / simplemap [s]
  bool tum_robot_poses = false;  ///< TUM poses are robot poses (composed with the mount)
  bool ego_available = true;     ///< the detector runs (ego-motion for "auto")
};

class PoseSource {
 public:
  virtual ~PoseSource() = default;
  /// Sensor pose in the world for `scan` (called once per scan, in order). `ego` = the detector's
  /// T_prev<-cur for this scan. Throws std::runtime_error when the scan has no pose.
  virtual Eigen::Isometry3d pose(const Scan& scan, const core::EgoMotion& ego) = 0;
  virtual std::string describe() const = 0;
};

/// Throws std::runtime_error for an unknown spec / file format, or a file that cannot be read.
std::unique_ptr<PoseSource> makePoseSource(const std::string& spec,
                                           const PoseSourceOptions& opts = {});

}  // namespace dynobj::mapclean
