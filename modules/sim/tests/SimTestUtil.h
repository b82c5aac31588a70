// SPDX-License-Identifier: BSD-3-Clause
// Shared by the simulator tests: a tiny noiseless sensor and scenario around it.
#pragma once

#include <dynobj/sim/Scenario.h>
#include <dynobj/testing/ScratchPath.h>
#include <mrpt/system/filesystem.h>

#include <cmath>
#include <fstream>
#include <string>

namespace dynobj::sim::test {

constexpr double kDeg = M_PI / 180.0;

/// 8 beams from +14 to -14 deg (4 deg apart), 64 columns, written to a temporary preset.
inline std::string tinySensorFile() {
  const std::string path = dynobj::testing::scratchPath("_tiny.ini");
  std::ofstream(path) << "[sensor]\nmodel = tiny\nrows = 8\ncols = 64\nelevation_top = 14\n"
                         "elevation_bottom = -14\nmin_range = 0.2\nmax_range = 80\n";
  return path;
}

/// A noiseless scenario: sensor at 1 m height, standing at the origin looking along +X.
inline std::string base(
    const std::string& extra,
    const std::string& platform = "{trajectory: {type: stationary, at: [0, 0]}}",
    const std::string& sensor_file = tinySensorFile()) {
  return "name: t\nframes: 10\nsensor: " + sensor_file +
         "\nmount: [0, 0, 1.0]\nnoise: {range_sigma: 0, dropout: 0, grazing_cos: 0}\n"
         "odometry: {enabled: false}\n"
         "floor: {size: [100, 100]}\n"
         "platform: " +
         platform + "\n" + extra;
}

inline Scenario load(const std::string& text) {
  return Scenario::fromYamlText(text, DYNOBJ_SHARE_DIR, {}, "test.yaml");
}

}  // namespace dynobj::sim::test
