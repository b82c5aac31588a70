// SPDX-License-Identifier: BSD-3-Clause
// The `procedural:` block of a scenario: its keys, and the generated world the loader then reads
// like a hand-written one (docs/simulator.md, "Procedural scenes").
#include <cmath>

#include "ScenarioLoader.h"
#include "dynobj/sim/Procedural.h"

namespace dynobj::sim::detail {
namespace {

ProceduralSpec::Count countOf(const YamlView& v, const std::string& key) {
  ProceduralSpec::Count c;
  if (!v.has(key)) return c;
  const auto [lo, hi] = rangeOf(v, key, 0, 0);
  if (lo < 0 || lo != std::floor(lo) || hi != std::floor(hi))
    v.child(key).fail("expected a whole number >= 0 or [lo, hi]");
  c.lo = static_cast<int>(lo);
  c.hi = static_cast<int>(hi);
  return c;
}

}  // namespace

const YamlView* Loader::loadProcedural(const YamlView& root) {
  if (!root.has("procedural")) return nullptr;
  const YamlView v = root.child("procedural");
  v.onlyKeys({"kind", "size", "pedestrians", "cyclists", "cars", "trees", "bushes", "fences",
              "pulling_out", "rider_groups", "two_wheelers", "standing", "occupancy", "crossing",
              "platform"});
  ProceduralSpec spec;
  try {
    spec.kind = ProceduralSpec::kindFromString(v.child("kind").scalar());
  } catch (const std::invalid_argument& e) {
    v.child("kind").fail(e.what());
  }
  if (v.has("size")) {
    spec.size = vec2(v, "size");
    if (!(spec.size.x() > 0 && spec.size.y() >= 0)) v.child("size").fail("sizes must be > 0");
  }
  spec.pedestrians = countOf(v, "pedestrians");
  spec.cyclists = countOf(v, "cyclists");
  spec.cars = countOf(v, "cars");
  spec.trees = countOf(v, "trees");
  spec.bushes = countOf(v, "bushes");
  spec.fences = countOf(v, "fences");
  spec.pulling_out = countOf(v, "pulling_out");
  spec.rider_groups = countOf(v, "rider_groups");
  spec.two_wheelers = countOf(v, "two_wheelers");
  spec.standing = v.num("standing", spec.standing);
  if (spec.standing < 0 || spec.standing > 1) v.child("standing").fail("must be in [0, 1]");
  spec.occupancy = v.num("occupancy", spec.occupancy);
  if (v.has("occupancy") && (spec.occupancy < 0 || spec.occupancy > 1))
    v.child("occupancy").fail("must be in [0, 1]");
  spec.crossing = v.flag("crossing", spec.crossing);
  if (v.has("platform")) {
    const YamlView p = v.child("platform");
    p.onlyKeys({"route", "speed"});
    spec.route = p.str("route", spec.route);
    if (p.has("speed")) spec.speed = positive(p, "speed", 1.0);
  }
  try {
    s_.world_yaml = generateWorld(spec, s_.seed, s_.duration());
  } catch (const std::invalid_argument& e) {
    (v.has("platform") ? v.child("platform") : v).fail(e.what());
  }
  world_doc_ = ::mrpt::containers::yaml::FromText(s_.world_yaml);
  world_ = std::make_unique<YamlView>(&world_doc_.node(), "procedural(world)");
  return world_.get();
}

}  // namespace dynobj::sim::detail
