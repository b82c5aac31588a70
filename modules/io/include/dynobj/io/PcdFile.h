// SPDX-License-Identifier: BSD-3-Clause
// PCD files (the Point Cloud Library's format, v0.5-v0.7): the project's one reader and writer.
// Reads DATA ascii, binary and binary_compressed (LZF), any scalar field type; writes binary
// x y z intensity (float32) atomically, optionally streaming points of unknown count.
#pragma once

#include <dynobj/io/AtomicFile.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>

#include "dynobj/io/CloudFile.h"
#include "dynobj/io/FormatError.h"

namespace dynobj::io {

/// Reads a PCD file. Needs fields x, y, z (COUNT 1); reads intensity (or i, or reflectivity),
/// ring and a time field (t, time or timestamp) when present; skips every other field, and fields
/// with COUNT > 1. Types F4 F8 U1 U2 U4 U8 I1 I2 I4 I8. Organized clouds (HEIGHT > 1) keep the
/// stored order. Bytes after the data are ignored (PCL pads files), a short data section is an
/// error. Throws FormatError "<path>: <problem>" (ascii data: "<path>:<line>: <problem>").
CloudFile readPcd(const std::string& path);

/// Writes a binary PCD v0.7 with fields x y z intensity (float32) through io::AtomicFile: the
/// file appears under its name only on close(). With `points` given, WIDTH and POINTS are written
/// up front (close() checks that many were added); without, a fixed-width blank field is reserved
/// and patched on close(), so memory stays flat whatever the count.
class PcdWriter {
 public:
  explicit PcdWriter(const std::string& path,
                     const Eigen::Isometry3d& viewpoint = Eigen::Isometry3d::Identity(),
                     const std::string& comment = "",
                     std::optional<std::size_t> points = std::nullopt);
  void add(float x, float y, float z, float intensity);
  std::size_t count() const { return count_; }
  /// Completes the header and renames the file into place. Throws FormatError when a count was
  /// announced and a different number of points was added. Not calling it leaves no file.
  void close();

 private:
  io::AtomicFile file_;
  std::optional<std::size_t> announced_;
  std::streampos width_pos_, points_pos_;
  std::size_t count_ = 0;
};

/// Writes `cloud` (intensity 0 when it has none) as one binary PCD; `comment` (optional) becomes
/// a '#' header line (dynobj stores "timestamp_ns <t>" there).
void writePcd(const std::string& path, const core::PointCloud& cloud,
              const Eigen::Isometry3d& viewpoint = Eigen::Isometry3d::Identity(),
              const std::string& comment = "");

}  // namespace dynobj::io
