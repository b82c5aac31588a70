// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFileMemory.h>

#include <cmath>

using namespace dynobj::core;

TEST(Config, ParsesValuesAndStripsComments) {
  mrpt::config::CConfigFileMemory cfg(
      "[a]\nd = 2.5 ; comment\ni = 7\nb = yes\nangle = 90\nlist = [1, 2 3]\ns = hello\n");
  EXPECT_DOUBLE_EQ(readDouble(cfg, "a", "d", 0), 2.5);
  EXPECT_EQ(readInt(cfg, "a", "i", 0), 7);
  EXPECT_TRUE(readBool(cfg, "a", "b", false));
  EXPECT_NEAR(readDegrees(cfg, "a", "angle", 0), M_PI / 2, 1e-12);
  EXPECT_EQ(readDoubleList(cfg, "a", "list"), (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(readString(cfg, "a", "s", ""), "hello");
  EXPECT_DOUBLE_EQ(readDouble(cfg, "a", "missing", 4.5), 4.5);
  EXPECT_TRUE(readDoubleList(cfg, "a", "missing").empty());
}

TEST(Config, BadValuesNameSectionAndKey) {
  mrpt::config::CConfigFileMemory cfg("[sec]\nd = 12abc\ni = 1.5\nb = maybe\n");
  for (const char* key : {"d", "i", "b"}) {
    try {
      if (std::string(key) == "d") readDouble(cfg, "sec", key, 0);
      if (std::string(key) == "i") readInt(cfg, "sec", key, 0);
      if (std::string(key) == "b") readBool(cfg, "sec", key, false);
      FAIL() << key;
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find(std::string("[sec] ") + key), std::string::npos)
          << e.what();
    }
  }
  try {
    readDouble(cfg, "sec", "needed", 0, true);
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("needed"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("missing"), std::string::npos);
  }
}

TEST(Config, RangeChecks) {
  EXPECT_NO_THROW(requireInRange("k", 1, 0, 2));
  EXPECT_THROW(requireInRange("k", 3, 0, 2), ParameterError);
  EXPECT_THROW(requireInRange("k", std::nan(""), 0, 2), ParameterError);
  EXPECT_THROW(requirePositive("k", 0), ParameterError);
}
