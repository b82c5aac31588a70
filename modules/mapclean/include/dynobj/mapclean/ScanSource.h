// SPDX-License-Identifier: BSD-3-Clause
// The scans to map, one at a time (memory stays flat): from an MRPT rawlog (LiDAR observations,
// with the latest odometry seen before each), or from a KTH DynamicMap benchmark folder
// (pcd/NNNNNN.pcd, points in the world, VIEWPOINT = sensor pose; re-projected into a LiDAR frame
// with a sensor model). Can be opened again (a second reader, or rewind()).
#pragma once

#include <dynobj/core/SensorModel.h>
#include <dynobj/mrptio/FrameSource.h>

#include <memory>
#include <optional>
#include <string>

namespace dynobj::mapclean {

/// A scan to map: SequenceRunner's frame (rawlog: the observation, its mount and the latest
/// odometry; PCD folder: the VIEWPOINT).
using Scan = mrptio::Frame;
/// Scans one at a time; rewind() for the next pass.
using ScanSource = mrptio::FrameSource;

struct ScanSourceOptions {
  std::string sensor_label;                 ///< rawlog: only this label (empty = every LiDAR one)
  std::optional<core::SensorModel> sensor;  ///< required for PCD folders and point clouds
};

/// "*.rawlog" (or any file MRPT reads as a rawlog) or a directory holding pcd/*.pcd. Anything
/// else is an error naming the input and the formats expected.
std::unique_ptr<ScanSource> openScanSource(const std::string& input, const ScanSourceOptions& opts);

}  // namespace dynobj::mapclean
