// SPDX-License-Identifier: BSD-3-Clause
// Procedural scenes: a random world generated from the scenario's seed (`procedural:` block,
// docs/simulator.md), so every seed is a different place - a street, a plaza, a room, a parking
// lot or a warehouse, with its buildings or walls, parked cars, trees, bushes, poles, fences, its
// crowd and traffic, and a route for the sensor platform that keeps clear of the obstacles.
// The world is produced as scenario YAML (floor, static, actors, platform) and read by the
// ordinary loader, so it obeys exactly the rules of hand-written scenes and can be frozen into a
// plain scenario file (`dynobj-sim --world`).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

namespace dynobj::sim {

struct ProceduralSpec {
  enum class Kind { Street, Plaza, Room, Parking, Warehouse } kind = Kind::Plaza;
  /// A count given as [lo, hi] (drawn per seed); lo < 0 = the kind's own default range.
  struct Count {
    int lo = -1, hi = -1;
  };
  Eigen::Vector2d size{0, 0};  ///< [m] extent along x, y; 0 = drawn from the kind's range
  Count pedestrians, cyclists, cars, trees, bushes, fences;
  Count pulling_out;  ///< parking: parked cars that drive away during the sequence
  /// street: groups of 3-6 riders (two-wheelers) riding close together along the kerb; none by
  /// default (0 = none drawn).
  Count rider_groups;
  /// street: two-wheelers parked on the sidewalk, most with someone standing beside; none by
  /// default.
  Count two_wheelers;
  double standing = 0.1;       ///< share of pedestrians that stand still all the time
  double occupancy = -1;       ///< parking: share of occupied slots; < 0 = drawn in [0.55, 0.85]
  bool crossing = false;       ///< street: a crossroad at x = 0
  std::string route = "auto";  ///< platform: auto, loop, cross, drive, stationary, corner
  double speed = -1;           ///< [m/s] platform speed; < 0 = the kind's default

  static Kind kindFromString(const std::string& name);  ///< throws std::invalid_argument
};

/// The world of `spec` for this seed, as scenario YAML with the top-level keys floor, static,
/// actors and platform. `duration` [s] bounds the start times drawn for actors. Deterministic:
/// the same spec and seed give the same text. Throws std::invalid_argument for a route the kind
/// does not offer.
std::string generateWorld(const ProceduralSpec& spec, std::uint32_t seed, double duration);

}  // namespace dynobj::sim
