// SPDX-License-Identifier: BSD-3-Clause
// TUM trajectory files: "timestamp tx ty tz qx qy qz qw" per line (seconds, metres), '#' comments.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynobj::core {

struct StampedPose {
  std::int64_t timestamp_ns = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

/// Reads a TUM file; throws std::runtime_error "<path>:<line>: <problem>" on a malformed line.
std::vector<StampedPose> readTumFile(const std::string& path);

/// The pose whose timestamp is within `tolerance_ns` of `t`, or nullptr.
const StampedPose* findPose(const std::vector<StampedPose>& poses, std::int64_t t,
                            std::int64_t tolerance_ns = 1000000);

}  // namespace dynobj::core
