// SPDX-License-Identifier: BSD-3-Clause
// A bird's-eye picture of a simulated sweep, to look at a (procedural) world and its ground truth.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "dynobj/sim/LidarSimulator.h"

namespace dynobj::sim {

/// Top-down view of `sweep` in the world frame (+x right, +y up), `metres_per_pixel` per pixel,
/// `half_extent` metres around the sensor: static returns grey (brighter = higher above the
/// floor), returns on standing actors blue, on moving actors red (the ground truth), the sensor
/// path `path` (world positions) green.
cv::Mat topView(const SimulatedSweep& sweep, const std::vector<Eigen::Vector3d>& path,
                double metres_per_pixel = 0.1, double half_extent = 40.0);

}  // namespace dynobj::sim
