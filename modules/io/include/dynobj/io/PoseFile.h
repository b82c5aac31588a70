// SPDX-License-Identifier: BSD-3-Clause
// Trajectory files: KITTI odometry poses (12 numbers a line: the 3x4 matrix [R | t] row by row,
// no time stamps) and TUM (8 numbers: t tx ty tz qx qy qz qw, t in seconds); '#' comments. The
// project's one TUM reader (readPoseFile), writer (TumWriter) and time lookup (findPose).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/io/AtomicFile.h"
#include "dynobj/io/FormatError.h"

namespace dynobj::io {

struct TimedPose {
  /// Nanoseconds; -1 for KITTI files, which carry no time: pose k belongs to sweep k (pair them
  /// with CloudFolder::timestampNs(k)).
  std::int64_t timestamp_ns = -1;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

enum class PoseFormat { Auto, Kitti, Tum };

/// Reads a pose file. Auto: the first data line's column count decides (12 = KITTI, 8 = TUM);
/// every later line must have as many. Rotations are re-orthonormalized. Throws FormatError
/// "<path>:<line>: <problem>" for a ragged line, a non-number, a non-unit quaternion (|q| off by
/// more than 1e-3), a 3x3 part that is not a rotation (|R'R - I| > 1e-3 or det < 0), TUM stamps
/// not increasing; "<path>: <problem>" for a missing file or one without poses.
std::vector<TimedPose> readPoseFile(const std::string& path, PoseFormat format = PoseFormat::Auto);

/// The pose whose timestamp is within `tolerance_ns` of `t` (the nearest), or nullptr. `poses`
/// sorted by time (as readPoseFile returns a TUM file).
const TimedPose* findPose(const std::vector<TimedPose>& poses, std::int64_t t,
                          std::int64_t tolerance_ns = 1000000);

/// Streams a TUM file through an AtomicFile: "# timestamp tx ty tz qx qy qz qw  (<note>)", then
/// one line a pose, the time with 9 decimals, the rest with 6.
class TumWriter {
 public:
  TumWriter(const std::string& path, const std::string& note);
  void write(std::int64_t timestamp_ns, const Eigen::Isometry3d& pose);
  /// Renames into place; throws std::runtime_error on an I/O error.
  void close() { file_.commit(); }

 private:
  AtomicFile file_;
};

/// A time in seconds as text ("1317354879.123456789", "0.1", "1.036602e-01") in nanoseconds;
/// plain decimals are converted exactly, exponent forms through double. nullopt if not a number.
std::optional<std::int64_t> parseSecondsNs(const std::string& text);

}  // namespace dynobj::io
