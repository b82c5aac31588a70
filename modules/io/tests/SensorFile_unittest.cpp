// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/io/VelodyneSensor.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

using dynobj::core::ParameterError;
using dynobj::core::SensorModel;

TEST(SensorModel, MissingFileOrSectionIsAClearError) {
  EXPECT_THROW(dynobj::io::readSensorModel("/nonexistent/x.ini"), ParameterError);
  try {
    dynobj::io::readSensorModel(std::string(DYNOBJ_SHARE_DIR) + "/sensors/os0-64.ini", "nope");
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("[nope]"), std::string::npos) << e.what();
  }
}

TEST(SensorModel, EveryShippedPresetLoads) {
  const std::string dir = std::string(DYNOBJ_SHARE_DIR) + "/sensors/";
  struct Expect {
    const char* file;
    int rows, cols;
  };
  for (const Expect& e : {Expect{"os0-64.ini", 64, 1024}, Expect{"os0-128.ini", 128, 1024},
                          Expect{"os0-64-512.ini", 64, 512}, Expect{"os0-128-2048.ini", 128, 2048},
                          Expect{"os1-64.ini", 64, 1024}, Expect{"vlp-16.ini", 16, 1800},
                          Expect{"hdl-32.ini", 32, 2048}, Expect{"hdl-64.ini", 64, 2048},
                          Expect{"vls-128.ini", 128, 1800}}) {
    SCOPED_TRACE(e.file);
    const SensorModel m = dynobj::io::readSensorModel(dir + e.file);
    EXPECT_EQ(m.rows, e.rows);
    EXPECT_EQ(m.cols, e.cols);
    const auto el = m.rowElevations();
    for (std::size_t i = 1; i < el.size(); i++) EXPECT_LT(el[i], el[i - 1]);
  }
}

TEST(SensorModel, VelodynePresetsCarryThePcapDecodersBeamTables) {
  // One beam table per model: a preset and dynobj-import's pcap decoder agree laser by laser.
  using dynobj::io::VelodyneModel;
  const std::string dir = std::string(DYNOBJ_SHARE_DIR) + "/sensors/";
  for (const auto& [file, model] : {std::pair{"vlp-16.ini", VelodyneModel::VLP16},
                                    std::pair{"hdl-32.ini", VelodyneModel::HDL32E},
                                    std::pair{"vls-128.ini", VelodyneModel::VLS128}}) {
    SCOPED_TRACE(file);
    const SensorModel m = dynobj::io::readSensorModel(dir + file);
    const auto table = dynobj::io::VelodyneSensor::of(model).elevation_deg;
    ASSERT_EQ(m.beam_elevations.size(), table.size());
    for (std::size_t l = 0; l < table.size(); l++)
      EXPECT_NEAR(m.beam_elevations[l] * 180.0 / M_PI, table[l], 1e-9) << "laser " << l;
  }
}
