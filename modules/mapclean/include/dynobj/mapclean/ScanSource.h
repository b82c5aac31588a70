// SPDX-License-Identifier: BSD-3-Clause
// The scans to map, one at a time (memory stays flat): from an MRPT rawlog (LiDAR observations,
// with the latest odometry seen before each), or from a KTH DynamicMap benchmark folder
// (pcd/NNNNNN.pcd, points in the world, VIEWPOINT = sensor pose; re-projected into a LiDAR frame
// with a sensor model). Can be opened again for a second pass.
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/SensorModel.h>
#include <mrpt/obs/CObservation.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

namespace dynobj::mapclean {

struct Scan {
  std::size_t index = 0;   ///< LiDAR scan number in the input (0-based)
  std::string where;       ///< for messages: "entry 12" or "pcd/000012.pcd"
  core::LidarFrame frame;  ///< sensor frame; frame.timestamp_ns is the scan time
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  ///< sensor pose on the robot
  std::optional<Eigen::Isometry3d> odometry;   ///< robot pose of the latest odometry (rawlog)
  std::optional<Eigen::Isometry3d> viewpoint;  ///< sensor pose given by the input (PCD VIEWPOINT)
  ::mrpt::obs::CObservation::Ptr observation;  ///< the rawlog's observation (null for PCD input)
};

class ScanSource {
 public:
  virtual ~ScanSource() = default;
  /// Next scan; false at the end. Throws with the file and entry named on bad input.
  virtual bool next(Scan& scan) = 0;
  /// Starts again from the first scan.
  virtual void rewind() = 0;
  virtual std::string describe() const = 0;
};

struct ScanSourceOptions {
  std::string sensor_label;                 ///< rawlog: only this label (empty = every LiDAR one)
  std::optional<core::SensorModel> sensor;  ///< required for PCD folders and point clouds
};

/// "*.rawlog" (or any file MRPT reads as a rawlog) or a directory holding pcd/*.pcd. Anything
/// else is an error naming the input and the formats expected.
std::unique_ptr<ScanSource> openScanSource(const std::string& input, const ScanSourceOptions& opts);

}  // namespace dynobj::mapclean
