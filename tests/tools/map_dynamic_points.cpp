// SPDX-License-Identifier: BSD-3-Clause
// Test tool: how many points of a map (MRPT points-map text dump, world frame) lie on the moving
// actors of a simulated sequence (mapclean::ActorPoints: within 0.2 m of a ground-truth dynamic
// point and more than 0.25 m above the floor). Compares a map built
// from the raw rawlog with one built from the filtered rawlog and fails unless the filtered map
// holds at most `max_ratio` times as many such points.
//   map_dynamic_points <seq.rawlog> <seq.gt.labels> <seq.gt.tum> <raw_map.txt> <filtered_map.txt>
//   <max_ratio>
#include <dynobj/mapclean/MapComparison.h>
#include <dynobj/mrptio/RawlogFrameSource.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  if (argc != 7) {
    std::fprintf(stderr,
                 "usage: map_dynamic_points seq.rawlog seq.gt.labels seq.gt.tum raw_map.txt "
                 "filtered_map.txt max_ratio\n");
    return 2;
  }
  try {
    namespace mc = dynobj::mapclean;
    dynobj::mrptio::RawlogFrameSource source(argv[1], dynobj::mrptio::ObservationConverter(),
                                             {"LIDAR", 0, 1000000});
    const auto actors = mc::ActorPoints::fromSequence(source, argv[2], argv[3]);
    const auto r = mc::countOnActors(mc::readPointsMapText(argv[4]), actors);
    const auto f = mc::countOnActors(mc::readPointsMapText(argv[5]), actors);
    const std::size_t raw = r.on_actors, raw_total = r.points, filtered = f.on_actors,
                      filtered_total = f.points;
    const double max_ratio = std::stod(argv[6]);
    std::printf(
        "map points on moving actors: raw map %zu (of %zu), filtered map %zu (of %zu), ratio %.2f "
        "(max %.2f)\n",
        raw, raw_total, filtered, filtered_total,
        raw ? static_cast<double>(filtered) / static_cast<double>(raw) : 0.0, max_ratio);
    return raw > 0 && static_cast<double>(filtered) <= max_ratio * static_cast<double>(raw) ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "map_dynamic_points: error: %s\n", e.what());
    return 1;
  }
}
