// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/core/DynamicObjectDetector.h>
#include <gtest/gtest.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/config/CConfigFileMemory.h>

using namespace dynobj::core;

namespace {
std::string dump(const DetectorParams& p) {
  ::mrpt::config::CConfigFileMemory m;
  p.save(m);
  return m.getContent();
}
}  // namespace

namespace {
/// (section, key) pairs of an INI file.
std::vector<std::pair<std::string, std::string>> keysOf(const ::mrpt::config::CConfigFileBase& c) {
  std::vector<std::pair<std::string, std::string>> out;
  std::vector<std::string> sections, keys;
  c.getAllSections(sections);
  for (const auto& s : sections) {
    c.getAllKeys(s, keys);
    for (const auto& k : keys) out.emplace_back(s, k);
  }
  return out;
}
}  // namespace

// The shipped dynobj.ini holds the keys a user may need (a person reads it in a minute) and loads
// to exactly the built-in defaults; advanced.ini lists every key, with its default.
TEST(DetectorParams, ShippedIniHoldsFewKeysAtTheirDefaults) {
  ::mrpt::config::CConfigFile cfg(std::string(DYNOBJ_SHARE_DIR) + "/config/dynobj.ini");
  DetectorParams loaded;
  loaded.load(cfg);
  EXPECT_EQ(dump(loaded), dump(DetectorParams{}));
  EXPECT_LE(keysOf(cfg).size(), 25u);
}

TEST(DetectorParams, AdvancedIniListsEveryKeyAtItsDefault) {
  ::mrpt::config::CConfigFile cfg(std::string(DYNOBJ_SHARE_DIR) + "/config/advanced.ini");
  DetectorParams loaded;
  loaded.load(cfg);
  EXPECT_EQ(dump(loaded), dump(DetectorParams{}));
  ::mrpt::config::CConfigFileMemory all;
  DetectorParams{}.save(all);
  for (const auto& [s, k] : keysOf(all))
    EXPECT_TRUE(cfg.keyExists(s, k)) << "[" << s << "] " << k << " missing from advanced.ini";
}

TEST(DetectorParams, SaveLoadRoundTripWithPrefix) {
  DetectorParams p;
  p.movement.window = 9;
  p.movement.long_object_angle = 0.3;
  p.tracking.hysteresis = false;
  p.free_space.enabled = false;
  ::mrpt::config::CConfigFileMemory m;
  p.save(m, "dynobj_");
  DetectorParams q;
  q.load(m, "dynobj_");
  EXPECT_EQ(dump(q), dump(p));
  EXPECT_EQ(q.movement.window, 9);
  EXPECT_NEAR(q.movement.long_object_angle, 0.3, 1e-7);  // written in degrees, 9 digits
}

TEST(DetectorParams, BadValuesNameSectionAndKey) {
  ::mrpt::config::CConfigFileMemory m("[movement]\nwindow = 1\n");
  DetectorParams p;
  try {
    p.load(m);
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("[movement] window"), std::string::npos) << e.what();
  }
  EXPECT_EQ(p.movement.window, MovementParams{}.window);  // a failed load changes nothing
  ::mrpt::config::CConfigFileMemory m2("[region_growing]\ndistance = -1\n");
  try {
    p.load(m2);
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("[region_growing] distance"), std::string::npos)
        << e.what();
  }
  ::mrpt::config::CConfigFileMemory m3("[pipeline]\nthreads = 3\n");
  try {
    p.load(m3);
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("[pipeline] threads"), std::string::npos) << e.what();
  }
}

TEST(DetectorParams, SensorPresetOverridesOnlyItsKeys) {
  ::mrpt::config::CConfigFile cfg(std::string(DYNOBJ_SHARE_DIR) +
                                  "/config/dynobj-os0-128-2048.ini");
  DetectorParams p;
  p.load(cfg);
  EXPECT_EQ(p.foreground.kernel_half_width, 14);
  EXPECT_EQ(p.ego_motion.match_window, 128);
  EXPECT_EQ(p.movement.window, MovementParams{}.window);  // everything else stays the default
}
