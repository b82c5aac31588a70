// SPDX-License-Identifier: BSD-3-Clause
// MRPT LiDAR observations -> core::LidarFrame. Supported (docs/formats.md has the per-type rules):
//  - CObservation3DRangeScan in the organized LiDAR layout (points3D_idxs give each point's pixel);
//  - CObservationVelodyneScan (laser_id -> row through its calibration, azimuth -> column);
//  - CObservationPointCloud (any CPointsMap, intensity from CPointsMapXYZI) via Eq. (1);
//  - CObservationRotatingScan (range + intensity images; beam elevations from the sensor model).
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/SensorModel.h>
#include <dynobj/core/SphericalProjection.h>
#include <mrpt/obs/CObservation.h>

#include <map>
#include <optional>
#include <stdexcept>
#include <string>

namespace dynobj::mrptio {

/// A malformed or unsupported observation. what() = "<class> '<sensorLabel>': <problem>".
class ConversionError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ObservationConverter {
 public:
  /// Without a sensor model: only self-describing observations (3D range scans with points,
  /// Velodyne scans with calibration) can be converted.
  ObservationConverter() = default;
  /// `sensor` describes the LiDAR for observations that do not carry their own geometry
  /// (point clouds, rotating scans, 3D range scans without points) and fixes the column count
  /// of Velodyne scans. It is validated here (throws core::ParameterError).
  explicit ObservationConverter(std::optional<core::SensorModel> sensor);

  /// True for the four LiDAR observation classes above (whether or not they are well formed).
  static bool isLidarObservation(const mrpt::obs::CObservation& obs);

  /// Fills `frame` (resized as needed; its memory is reused across calls). Loads externally
  /// stored data first. Throws ConversionError for an unsupported class or malformed content
  /// (size mismatches, missing geometry, no points, ...).
  core::ProjectionStats convert(const mrpt::obs::CObservation& obs, core::LidarFrame& frame) const;

  const std::optional<core::SensorModel>& sensor() const { return sensor_; }

 private:
  std::optional<core::SensorModel> sensor_;
  /// Without a sensor model: the rows recovered from the first complete point cloud of each
  /// sensor label, the hint for its later ones (so a partial sweep keeps the sensor's rows).
  /// Not shared between threads: give each thread its own converter.
  mutable std::map<std::string, core::SensorModel> learned_;
};

}  // namespace dynobj::mrptio
