// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/core/SensorModel.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <mrpt/system/filesystem.h>

#include <cmath>
#include <string>

using dynobj::core::ParameterError;
using dynobj::core::SensorModel;

namespace {

constexpr double kDeg = M_PI / 180.0;

std::string errorOf(const std::string& ini) {
  mrpt::config::CConfigFileMemory cfg(ini);
  SensorModel m;
  try {
    m.loadFromConfigFile(cfg, "sensor");
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SensorModel, LoadsDegreesAsRadians) {
  mrpt::config::CConfigFileMemory cfg(
      "[sensor]\nmodel = VLP-16\nrows = 16\ncols = 1800\nelevation_top = 15 ; deg\n"
      "elevation_bottom = -15\nmax_range = 100\nmin_range = 0.5\nfrequency = 10\n");
  SensorModel m;
  m.loadFromConfigFile(cfg, "sensor");
  EXPECT_EQ(m.model, "VLP-16");
  EXPECT_EQ(m.rows, 16);
  EXPECT_EQ(m.cols, 1800);
  EXPECT_NEAR(m.elevation_top, 15 * kDeg, 1e-12);
  EXPECT_NEAR(m.fovUp(), 16 * kDeg, 1e-12);
  EXPECT_NEAR(m.fovSpan(), 32 * kDeg, 1e-12);
  const auto e = m.rowElevations();
  ASSERT_EQ(e.size(), 16u);
  EXPECT_NEAR(e[1], 13 * kDeg, 1e-12);
  EXPECT_NEAR(e[15], -15 * kDeg, 1e-12);
}

TEST(SensorModel, SaveLoadRoundTrip) {
  SensorModel a;
  a.model = "table";
  a.rows = 3;
  a.cols = 100;
  a.beam_elevations = {-2 * kDeg, 4 * kDeg, 1 * kDeg};
  a.max_range = 55;
  mrpt::config::CConfigFileMemory cfg;
  a.saveToConfigFile(cfg, "s");
  SensorModel b;
  b.loadFromConfigFile(cfg, "s");
  EXPECT_EQ(b.model, a.model);
  EXPECT_EQ(b.rows, 3);
  ASSERT_EQ(b.beam_elevations.size(), 3u);
  for (std::size_t i = 0; i < 3; i++) EXPECT_NEAR(b.beam_elevations[i], a.beam_elevations[i], 1e-9);
  EXPECT_EQ(b.laserToRow(), (std::vector<int>{2, 0, 1}));
  EXPECT_DOUBLE_EQ(b.max_range, 55);
}

TEST(SensorModel, ErrorsNameTheKey) {
  EXPECT_NE(errorOf("[sensor]\ncols = 10\nelevation_top=1\nelevation_bottom=-1\n").find("rows"),
            std::string::npos);
  EXPECT_NE(errorOf("[sensor]\nrows = abc\ncols=10\n").find("rows"), std::string::npos);
  EXPECT_NE(errorOf("[sensor]\nrows = 4\ncols = 16\nelevation_top = 1\n").find("elevation_bottom"),
            std::string::npos);
  EXPECT_NE(errorOf("[sensor]\nrows = 4\ncols = 16\nelevation_top = -5\nelevation_bottom = 5\n")
                .find("elevation_top"),
            std::string::npos);
  EXPECT_NE(
      errorOf("[sensor]\nrows = 4\ncols = 16\nbeam_elevations = 1 2 3\n").find("beam_elevations"),
      std::string::npos);
  EXPECT_NE(
      errorOf("[sensor]\nrows = 2\ncols = 16\nbeam_elevations = 1 1\n").find("beam_elevations"),
      std::string::npos);
  EXPECT_NE(errorOf("[sensor]\nrows = 4\ncols = 16\nelevation_top=1\nelevation_bottom=-1\n"
                    "max_range = -3\n")
                .find("max_range"),
            std::string::npos);
  EXPECT_EQ(errorOf("[sensor]\nrows = 4\ncols = 16\nelevation_top=1\nelevation_bottom=-1\n"), "");
}
