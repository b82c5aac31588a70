// SPDX-License-Identifier: BSD-3-Clause
// Point-cloud files, without MRPT: PCD v0.7 (the KTH DynamicMap benchmark's format: fields
// x y z intensity, VIEWPOINT = sensor pose as "tx ty tz qw qx qy qz") and binary PLY.
// Every writer is atomic (core::AtomicFile): a file with the final name is complete.
#pragma once

#include <dynobj/core/AtomicFile.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {

/// A malformed or unsupported point-cloud file; what() = "<path>: <problem>" (or "<path>:<line>:").
class PointCloudFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct PcdCloud {
  std::vector<MapPoint> points;
  Eigen::Isometry3d viewpoint = Eigen::Isometry3d::Identity();  ///< VIEWPOINT (sensor pose)
  bool has_intensity = false;
  std::vector<std::string> comments;  ///< header comment lines after the first, without '#'
};

/// Reads a PCD file (DATA ascii or binary; binary_compressed is refused). Needs fields x, y, z;
/// reads `intensity` when present; skips other fields. Throws PointCloudFileError.
PcdCloud readPcd(const std::string& path);

/// Writes a binary PCD (fields x y z intensity, float) atomically.
/// `comment` (optional) becomes a '#' header line (readers skip it; dynobj stores the timestamp).
void writePcd(const std::string& path, const std::vector<MapPoint>& points,
              const Eigen::Isometry3d& viewpoint = Eigen::Isometry3d::Identity(),
              const std::string& comment = "");

/// Streams points into a binary PCD whose size is not known in advance (e.g. the benchmark's
/// gt_cloud.pcd): the point count is patched into the header on close(), then the file is renamed
/// into place. Memory stays flat.
class PcdStreamWriter {
 public:
  explicit PcdStreamWriter(const std::string& path,
                           const Eigen::Isometry3d& viewpoint = Eigen::Isometry3d::Identity());
  void add(const MapPoint& p);
  std::size_t count() const { return count_; }
  void close();

 private:
  core::AtomicFile file_;
  std::streampos width_pos_, points_pos_;
  std::size_t count_ = 0;
};

/// Writes a binary little-endian PLY (vertex x y z intensity, float) atomically.
void writePly(const std::string& path, const std::vector<MapPoint>& points);

}  // namespace dynobj::mapclean
