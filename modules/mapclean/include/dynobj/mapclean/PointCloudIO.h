// SPDX-License-Identifier: BSD-3-Clause
// Point-cloud files of the map cleaner, in MapPoint form: PCD v0.7 (the KTH DynamicMap
// benchmark's format: fields x y z intensity, VIEWPOINT = sensor pose as "tx ty tz qw qx qy qz")
// and binary PLY. The PCD reading and writing itself is dynobj::io's (PcdFile.h); these adapt it.
// Every writer is atomic (io::AtomicFile): a file with the final name is complete.
#pragma once

#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/FormatError.h>
#include <dynobj/io/PcdFile.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <string>
#include <vector>

#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {

/// A malformed or unsupported point-cloud file; what() = "<path>: <problem>" (or "<path>:<line>:").
using PointCloudFileError = io::FormatError;

struct PcdCloud {
  std::vector<MapPoint> points;
  Eigen::Isometry3d viewpoint = Eigen::Isometry3d::Identity();  ///< VIEWPOINT (sensor pose)
  bool has_intensity = false;
  std::vector<std::string> comments;  ///< header comments but the ".PCD" banner, without '#'
};

/// Reads a PCD file through io::readPcd (every DATA layout; needs fields x, y, z; intensity from
/// `intensity`, `i` or `reflectivity` when present; NaN points dropped). Throws
/// PointCloudFileError.
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
  std::size_t count() const { return writer_.count(); }
  void close();

 private:
  io::PcdWriter writer_;
};

/// Streams points into a binary little-endian PLY (vertex x y z intensity, float) whose size is
/// not known in advance: the vertex count is patched into the header by finish() (a padded comment
/// line after it keeps the header's length). commit() renames the file into place; destroyed
/// uncommitted, it leaves nothing. Memory stays flat.
class PlyStreamWriter {
 public:
  explicit PlyStreamWriter(const std::string& path);
  void add(const MapPoint& p);
  std::size_t count() const { return count_; }
  /// Completes the header and flushes: partialPath() is then a whole PLY file (readPly).
  void finish();
  const std::string& partialPath() const { return file_.partialPath(); }
  /// finish(), then renames the file into place. Throws std::runtime_error on an I/O error.
  void commit();

 private:
  io::AtomicFile file_;
  std::streampos count_pos_;
  std::size_t count_ = 0;
};

/// Writes a binary little-endian PLY (vertex x y z intensity, float) atomically.
void writePly(const std::string& path, const std::vector<MapPoint>& points);

/// Reads a binary little-endian PLY whose vertices are float properties including x, y, z (and
/// `intensity`, else 0), e.g. writePly()'s. Throws PointCloudFileError naming the file and what it
/// holds instead (ASCII, big-endian, a non-float property, a truncated body).
std::vector<MapPoint> readPly(const std::string& path);

}  // namespace dynobj::mapclean
