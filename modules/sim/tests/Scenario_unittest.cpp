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
  EXPECT_NE(errorOf(kMinimal, {{"noise.range_sigma", "1"}}).find("no key 'noise'"),
            std::string::npos);
  EXPECT_NE(errorOf("- a\n- b\n").find("not a map of key: value"), std::string::npos);
}

TEST(Scenario, EveryShippedScenarioLoads) {
  for (const char* name : {"hall", "corridor", "crossing", "street", "static"}) {
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
