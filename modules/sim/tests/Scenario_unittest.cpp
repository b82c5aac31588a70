// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/sim/Scenario.h>
#include <gtest/gtest.h>

using namespace dynobj::sim;

namespace {

const std::string kMinimal =
    "name: tiny\nframes: 5\nsensor: sensors/vlp-16.ini\n"
    "platform: {trajectory: {type: stationary, at: [0, 0]}}\n";

std::string errorOf(const std::string& text, const std::map<std::string, std::string>& ov = {}) {
  try {
    Scenario::fromYamlText(text, DYNOBJ_SHARE_DIR, ov, "t.yaml");
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Scenario, MinimalAndOverrides) {
  const Scenario s = Scenario::fromYamlText(kMinimal, DYNOBJ_SHARE_DIR, {}, "t.yaml");
  EXPECT_EQ(s.name, "tiny");
  EXPECT_EQ(s.frames, 5);
  EXPECT_EQ(s.sensor.rows, 16);
  const Scenario o = Scenario::fromYamlText(
      kMinimal + "noise: {range_sigma: 0.02}\n", DYNOBJ_SHARE_DIR,
      {{"frames", "9"}, {"noise.range_sigma", "0.05"}, {"seed", "3"}}, "t.yaml");
  EXPECT_EQ(o.frames, 9);
  EXPECT_DOUBLE_EQ(o.range_sigma, 0.05);
  EXPECT_EQ(o.seed, 3u);
}

TEST(Scenario, TextThatIsNotUtf8IsRefusedBeforeParsing) {
  // fuzz_scenario_yaml: a malformed byte inside a `%` directive made libfyaml loop forever.
  EXPECT_EQ(errorOf("% x\xc9 y\n"),
            "t.yaml: not valid UTF-8 at line 1 (byte 3); YAML text must be UTF-8");
  EXPECT_EQ(errorOf(kMinimal + "# caf\xc3\n"),
            "t.yaml: not valid UTF-8 at line 5 (byte 108); YAML text must be UTF-8");
  EXPECT_NE(errorOf(kMinimal + "# caf\xed\xa0\x80\n").find("not valid UTF-8"),
            std::string::npos);  // surrogate
  EXPECT_EQ(errorOf(kMinimal + "# caf\xc3\xa9 \xe2\x82\xac \xf0\x9f\x9a\x97\n"),
            "");  // well-formed
  EXPECT_EQ(errorOf(kMinimal, {{"name", "a\xff"}}),
            "override: not valid UTF-8 at line 1 (byte 6); YAML text must be UTF-8");
}

TEST(Scenario, ActorsFromGroups) {
  const Scenario s = Scenario::fromYamlText(
      kMinimal +
          "actors:\n"
          "  - {class: pedestrian, count: 3, trajectory: {type: random_walk, region: "
          "[-5,-5,5,5]}}\n"
          "  - {class: car, trajectory: {type: waypoints, points: [[0,0],[10,0]], speed: 5}}\n",
      DYNOBJ_SHARE_DIR, {}, "t.yaml");
  ASSERT_EQ(s.actors.size(), 4u);
  EXPECT_EQ(s.actors[3].cls, ActorClass::Car);
  EXPECT_EQ(s.actors[2].id, 2);
  EXPECT_FALSE(s.actors[0].parts.empty());
}

TEST(Scenario, ErrorsNameFileAndKey) {
  EXPECT_NE(errorOf(kMinimal + "frams: 3\n").find("t.yaml: (root): unknown key 'frams'"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "noise: {range_sigma: lots}\n")
                .find("noise.range_sigma: 'lots' is not a number"),
            std::string::npos);
  EXPECT_NE(errorOf("name: x\n").find("platform: required key is missing"), std::string::npos);
  EXPECT_NE(errorOf(kMinimal +
                    "actors:\n  - {class: dragon, trajectory: {type: stationary, at: [0,0]}}\n")
                .find("actors[0].class: unknown class 'dragon'"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "static:\n  - {box: {center: [0, 0], size: [1, 1, 1]}}\n")
                .find("static[0].box.center: expected 3 numbers"),
            std::string::npos);
  EXPECT_NE(errorOf("name: x\nsensor: sensors/none.ini\nplatform: {trajectory: {type: stationary, "
                    "at: [0,0]}}\n")
                .find("none.ini"),
            std::string::npos);
  // An override may create a missing block; a misspelt one is still an unknown key.
  EXPECT_EQ(errorOf(kMinimal, {{"noise.range_sigma", "1"}}), "");
  EXPECT_NE(errorOf(kMinimal, {{"nois.range_sigma", "1"}}).find("unknown key 'nois'"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "intensity: {model: lidar}\n").find("intensity.model: unknown"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "output: pcd\n").find("output: unknown output 'pcd'"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "static:\n  - {tree: {center: [0, 0], density: -1}}\n")
                .find("static[0].tree.density: must be > 0"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "static:\n  - {fence: {from: [0, 0], to: [3, 0], style: wood}}\n")
                .find("static[0].fence.style: unknown fence style 'wood'"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "static:\n  - {bush: {center: [0, 0], size: [1, 1]}}\n")
                .find("static[0].bush.size: expected 3 numbers"),
            std::string::npos);
  EXPECT_NE(errorOf(kMinimal + "sensor_unit: {elevation_sigma_deg: -0.1}\n")
                .find("sensor_unit.elevation_sigma_deg: must be >= 0"),
            std::string::npos);
  EXPECT_NE(errorOf("- a\n- b\n").find("not a map of key: value"), std::string::npos);
}

TEST(Scenario, EveryShippedScenarioLoads) {
  for (const char* name : {"hall", "corridor", "crossing", "street", "static", "plaza", "parking",
                           "warehouse", "corner", "crowd", "traffic"}) {
    SCOPED_TRACE(name);
    const std::string path = std::string(DYNOBJ_SHARE_DIR) + "/scenarios/" + name + ".yaml";
    Scenario s;
    ASSERT_NO_THROW(s = Scenario::fromYamlFile(path, DYNOBJ_SHARE_DIR));
    EXPECT_EQ(s.name, name);
    EXPECT_GE(s.frames, 100);
    if (std::string(name) == "static") {
      for (const Actor& a : s.actors) EXPECT_EQ(a.track.keys().size(), 1u);
    } else {
      EXPECT_FALSE(s.actors.empty());
    }
  }
}

TEST(Scenario, OverrideCreatesMissingBlocks) {
  const Scenario s = Scenario::fromYamlText(
      kMinimal, DYNOBJ_SHARE_DIR, {{"intensity.model", "velodyne"}, {"noise.dropout", "0.01"}},
      "t.yaml");
  EXPECT_EQ(s.intensity_model, IntensityModel::Velodyne);
  EXPECT_DOUBLE_EQ(s.dropout, 0.01);
  EXPECT_DOUBLE_EQ(s.range_sigma, 0.02);  // the rest of the block keeps its defaults
}

TEST(Scenario, TreesBushesAndFences) {
  const Scenario s = Scenario::fromYamlText(
      kMinimal +
          "static:\n"
          "  - {tree: {center: [3, 4], height: 8, crown_radius: 2, crown_height: 4, density: "
          "1.5}}\n"
          "  - {bush: {center: [1, 1], size: [2, 1, 1.2], shape: box}}\n"
          "  - {fence: {from: [0, 5], to: [10, 5], style: railing, height: 1.0}}\n",
      DYNOBJ_SHARE_DIR, {}, "t.yaml");
  ASSERT_EQ(s.statics.size(), 4u);  // trunk + crown, bush, fence
  EXPECT_EQ(s.statics[0].kind, Part::Kind::Cylinder);
  EXPECT_DOUBLE_EQ(s.statics[0].cylinder.z1, 6.0);  // into the crown's centre
  EXPECT_EQ(s.statics[1].kind, Part::Kind::Porous);
  EXPECT_TRUE(s.statics[1].porous.ellipsoid);
  EXPECT_DOUBLE_EQ(s.statics[1].porous.center.z(), 6.0);
  EXPECT_DOUBLE_EQ(s.statics[1].porous.half.x(), 2.0);
  EXPECT_DOUBLE_EQ(s.statics[1].porous.half.z(), 2.0);
  EXPECT_DOUBLE_EQ(s.statics[1].porous.density, 1.5);
  EXPECT_GT(s.statics[1].sway, 0.0);
  EXPECT_FALSE(s.statics[2].porous.ellipsoid);
  EXPECT_DOUBLE_EQ(s.statics[2].porous.center.z(), 0.6);  // standing on the ground
  EXPECT_EQ(s.statics[3].kind, Part::Kind::Fence);
  EXPECT_DOUBLE_EQ(s.statics[3].fence.bar_spacing, 1.5);  // railing: posts 1.5 m apart
  EXPECT_EQ(s.statics[3].fence.rail_count, 2);
  EXPECT_DOUBLE_EQ(s.statics[3].fence.rails[0], 0.5);
}
