// SPDX-License-Identifier: BSD-3-Clause
// Internal: reads a scenario YAML document into a Scenario (format: docs/simulator.md). Split
// over ScenarioLoader.cpp (scene, platform, actors) and ScenarioClutter.cpp (vegetation, fences,
// sensor traits).
#pragma once

#include <memory>
#include <random>
#include <string>
#include <utility>

#include "YamlView.h"
#include "dynobj/sim/Scenario.h"

namespace dynobj::sim::detail {

constexpr double kDeg = M_PI / 180.0;

/// A value given as one number or as a [lo, hi] range (is_range tells which).
std::pair<double, double> rangeOf(const YamlView& v, const std::string& key, double lo, double hi,
                                  bool* is_range = nullptr);
/// rangeOf(), drawn uniformly when a range.
double drawRange(const YamlView& v, const std::string& key, double def, std::mt19937& rng);
Eigen::Vector2d vec2(const YamlView& v, const std::string& key);
/// A number that must be > 0 (fails naming the key otherwise).
double positive(const YamlView& v, const std::string& key, double def);

class Loader {
 public:
  Loader(Scenario& s, std::string share_dir) : s_(s), share_(std::move(share_dir)) {}
  void load(const YamlView& root);

 private:
  /// The world of a `procedural:` block (generated from the seed), or null without one.
  const YamlView* loadProcedural(const YamlView& root);
  void loadSensor(const YamlView& root);
  void loadIntensity(const YamlView& root);
  void loadSensorUnit(const YamlView& root);
  void loadOutput(const YamlView& root);
  /// `realism: harsh` or a map of traits (`profile: harsh` first, then each key overrides).
  void loadRealism(const YamlView& root);
  Material material(const YamlView& owner, double albedo, Pattern pattern, double scale,
                    const std::string& key = "material");
  void loadFloor(const YamlView& root);
  void loadStatic(const YamlView& item);
  void loadTree(const YamlView& item);
  void loadBush(const YamlView& item);
  void loadFence(const YamlView& item);
  PoseTrack track(const YamlView& t, double start);
  /// `p` = the platform block (bob); `trajectory_owner` holds its `trajectory`.
  void loadPlatform(const YamlView& p, const YamlView& trajectory_owner);
  void loadActors(const YamlView& a);

  Scenario& s_;
  std::string share_;
  std::mt19937 rng_;
  std::uint32_t surfaces_ = 0;
  ::mrpt::containers::yaml world_doc_;
  std::unique_ptr<YamlView> world_;
};

}  // namespace dynobj::sim::detail
