// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/io/SensorFile.h>
#include <gtest/gtest.h>

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
                          Expect{"hdl-32.ini", 32, 2048}, Expect{"hdl-64.ini", 64, 2048}}) {
    SCOPED_TRACE(e.file);
    const SensorModel m = dynobj::io::readSensorModel(dir + e.file);
    EXPECT_EQ(m.rows, e.rows);
    EXPECT_EQ(m.cols, e.cols);
    const auto el = m.rowElevations();
    for (std::size_t i = 1; i < el.size(); i++) EXPECT_LT(el[i], el[i - 1]);
  }
}
