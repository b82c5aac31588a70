// SPDX-License-Identifier: BSD-3-Clause
// Internal: writes a procedural world as scenario YAML while keeping track of the space taken
// (footprints and the platform's corridor), so generated objects do not overlap each other or
// the sensor's route. Used by the layouts in ProceduralIndoor.cpp and ProceduralOutdoor.cpp.
#pragma once

#include <Eigen/Core>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "dynobj/sim/PoseTrack.h"
#include "dynobj/sim/Procedural.h"

namespace dynobj::sim::detail {

class WorldBuilder {
 public:
  WorldBuilder(const ProceduralSpec& spec, std::uint32_t seed, double duration);

  const ProceduralSpec& spec() const { return spec_; }
  double duration() const { return duration_; }
  double uni(double lo, double hi);
  int uniInt(int lo, int hi);  ///< inclusive
  bool chance(double p) { return uni(0, 1) < p; }
  /// The spec's count if given, else drawn in [def_lo, def_hi].
  int count(const ProceduralSpec::Count& c, int def_lo, int def_hi);
  /// The size along x, y: the spec's, or drawn in the given ranges.
  Eigen::Vector2d size(double xlo, double xhi, double ylo, double yhi);
  double platformSpeed(double def) const { return spec_.speed > 0 ? spec_.speed : def; }

  // Space bookkeeping.
  void keepOut(const std::vector<Eigen::Vector2d>& path, double half_width, bool closed);
  void keepOutDisc(const Eigen::Vector2d& c, double r) { occupied_.push_back({c, r}); }
  /// True when a disc of radius r at p overlaps nothing placed and no kept-out corridor.
  bool isFree(const Eigen::Vector2d& p, double r) const;
  /// A free spot in [xmin, xmax] x [ymin, ymax] (up to `tries` draws); false when none found.
  bool freeSpot(double xmin, double ymin, double xmax, double ymax, double r, Eigen::Vector2d& out,
                int tries = 40);

  // Emitters (positions in metres, angles in degrees). Solid objects also occupy their footprint.
  void floor(double sx, double sy, double albedo, const std::string& pattern, double scale);
  void box(double cx, double cy, double sx, double sy, double sz, double yaw_deg,
           const std::string& material, double z0 = 0);
  void cylinder(double cx, double cy, double r, double h, const std::string& material);
  void parkedCar(double cx, double cy, double yaw_deg);
  void tree(double cx, double cy, double h, double crown_r);
  void bush(double cx, double cy, double sx, double sy, double sz, double yaw_deg, bool hedge);
  void fence(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double h,
             const std::string& style);
  /// A random material line: albedo in [lo, hi], one of the patterns, scale in [slo, shi].
  std::string material(double lo, double hi, const std::vector<std::string>& patterns, double slo,
                       double shi);

  void walker(const Eigen::Vector4d& region, double speed_lo, double speed_hi, double pause_hi,
              double start = 0);
  void stander(const Eigen::Vector2d& at);
  /// A pedestrian, cyclist or car on waypoints. A vehicle whose footprint would come within the
  /// platform's radius of the sensor, or near another vehicle's footprint or a stander, at any
  /// time is not added (false): draw another. An added vehicle's path is kept out for what is
  /// placed later.
  bool mover(const std::string& cls, const std::vector<Eigen::Vector2d>& pts, double speed,
             bool loop, double start, double pause = 0);
  /// The closed loop `pts` entered at `phase` (0-1) of its length: a vehicle already on its way
  /// at the start, not one waiting at the first point until it sets off.
  static std::vector<Eigen::Vector2d> loopFrom(const std::vector<Eigen::Vector2d>& pts,
                                               double phase);
  /// The sensor platform (call before any mover). `radius` [m]: its body, kept clear of vehicles.
  void platform(const std::vector<Eigen::Vector2d>& pts, double speed, bool loop,
                double radius = 0.8);
  void platformStationary(const Eigen::Vector2d& at, double yaw_deg, double radius = 0.5);

  std::string yaml() const;

 private:
  struct Disc {
    Eigen::Vector2d c;
    double r;
  };
  struct Corridor {
    Eigen::Vector2d a, b;
    double half_width;
  };
  struct Vehicle {
    PoseTrack track;
    double hl, hw;  ///< [m] half length and half width of its footprint
    double start;   ///< [s] when it sets off
  };
  static constexpr double kStanderRadius = 0.5;  ///< [m] the disc a stander occupies
  /// No collision over the sequence with the platform, the vehicles added or a stander (two
  /// vehicles both still waiting at their first points, before `start`, do not count).
  bool clearOfOthers(const PoseTrack& track, double hl, double hw, double start) const;
  static std::string num(double v);
  static std::string point(const Eigen::Vector2d& p);

  ProceduralSpec spec_;
  double duration_;
  std::mt19937 rng_;
  std::vector<Disc> occupied_;
  std::vector<Corridor> corridors_;
  PoseTrack platform_track_;
  double platform_radius_ = 0;
  std::vector<Vehicle> vehicles_;
  std::vector<Eigen::Vector2d> standers_;
  std::ostringstream floor_, static_, actors_, platform_;
};

/// The layouts (one per kind).
void buildRoom(WorldBuilder& w);
void buildWarehouse(WorldBuilder& w);
void buildStreet(WorldBuilder& w);
void buildPlaza(WorldBuilder& w);
void buildParking(WorldBuilder& w);

}  // namespace dynobj::sim::detail
