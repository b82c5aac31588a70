// SPDX-License-Identifier: BSD-3-Clause
// CloudFile: one LiDAR sweep read from a point-cloud file (PCD, KITTI .bin), the common result of
// the readers in dynobj::io. Points stay in the file's (sensor) frame and order.
#pragma once

#include <dynobj/core/PointCloud.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace dynobj::io {

struct CloudFile {
  /// x, y, z [m] as stored; intensity (raw values, not rescaled) when the file has one; ring when
  /// the file has one. Points whose x, y or z is NaN or infinite are dropped (see below).
  core::PointCloud cloud;
  /// Per-point time [s] relative to the sweep when the file has t/time/timestamp, else empty.
  /// Units: an integer field (U/I) holds nanoseconds (Ouster `t`: U4 ns since the frame start), a
  /// float field (F) seconds (Velodyne `time`: F4 s). Absolute stamps (any |value| > 1e6 s) are
  /// made relative to the earliest point; time_origin_ns is then that earliest stamp (else 0).
  std::vector<float> time_s;
  std::int64_t time_origin_ns = 0;
  /// The field that fed cloud.intensity: "intensity", "i", "reflectivity" (first present in this
  /// order), or "" when none.
  std::string intensity_field;
  /// The time field read into time_s: "t", "time", "timestamp", or "".
  std::string time_field;
  /// PCD VIEWPOINT (sensor pose of the acquisition); identity for formats without one.
  Eigen::Isometry3d viewpoint = Eigen::Isometry3d::Identity();
  /// Grid size as stored: height > 1 = organized (rows of `width` points, row-major; the cloud
  /// keeps the stored order minus dropped points). Unorganized: width = points, height = 1.
  std::size_t width = 0, height = 1;
  /// NaN/inf points removed (counted, not an error).
  std::size_t dropped_nonfinite = 0;
  /// Header comment lines after the format's banner line, without the leading '#'.
  std::vector<std::string> comments;
};

}  // namespace dynobj::io
