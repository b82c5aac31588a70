// SPDX-License-Identifier: BSD-3-Clause
// Tiny hand-made LiDAR frames and a scratch folder for the mapclean tests.
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/SensorModel.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace dynobj::mapclean::test {

/// A path in the tests' scratch folder (created if missing).
inline std::string tmpPath(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / "dynobj-mapclean-tests";
  std::filesystem::create_directories(d);
  return (d / name).string();
}

/// 4 beams (+15, +5, -5, -15 deg) x 8 azimuth bins, uniform.
inline core::SensorModel tinySensor() {
  core::SensorModel s;
  s.model = "tiny";
  s.rows = 4;
  s.cols = 8;
  s.elevation_top = 15.0 * M_PI / 180.0;
  s.elevation_bottom = -15.0 * M_PI / 180.0;
  s.min_range = 0.1;
  s.max_range = 50;
  return s;
}

/// A frame with the given (row, col, x, y, z) returns (intensity = 10 * index).
inline core::LidarFrame tinyFrame(const std::vector<std::pair<std::pair<int, int>, cv::Vec3f>>& pts,
                                  std::int64_t t_ns = 0) {
  core::LidarFrame f(tinySensor());
  f.timestamp_ns = t_ns;
  int i = 0;
  for (const auto& [rc, p] : pts) {
    f.setPixel(rc.first, rc.second, static_cast<float>(cv::norm(p)), 10.f * static_cast<float>(i),
               p, i);
    i++;
  }
  return f;
}

}  // namespace dynobj::mapclean::test
