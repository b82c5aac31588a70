// SPDX-License-Identifier: BSD-3-Clause
// The tracks CSV (docs/formats.md): one row per frame and tracked object, written through an
// AtomicFile (complete or absent):
//   timestamp_ns,sensor_label,id,dynamic,age,points,x,y,z,vx,vy,min_x,min_y,min_z,max_x,max_y,max_z
// positions and boxes in the sensor frame [m], velocities [m/s].
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>

#include <string>

#include "dynobj/io/AtomicFile.h"

namespace dynobj::io {

class TracksCsvWriter {
 public:
  /// Opens "<path>.partial" and writes the header. Throws naming the file.
  explicit TracksCsvWriter(const std::string& path);
  /// Appends one row per object of `r`.
  void write(const std::string& sensor_label, const core::DetectionResult& r);
  /// Renames into place; throws std::runtime_error on an I/O error.
  void close() { file_.commit(); }

 private:
  AtomicFile file_;
};

}  // namespace dynobj::io
