// SPDX-License-Identifier: BSD-3-Clause
// dynobj-mapcompare: two maps of one labelled sequence (e.g. stock icp-slam on the raw and on the
// filtered rawlog): how many map points lie on the moving actors in each, and one top-down PNG of
// both side by side with those points in red. Ground truth: the sequence's label file and TUM
// sensor poses (dynobj-sim writes both); the detector never sees them.
#include <dynobj/io/Png.h>
#include <dynobj/mapclean/MapComparison.h>
#include <dynobj/mrptio/RawlogFrameSource.h>

#include <cstdio>

#include "../common/AppOptions.h"

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-mapcompare: map points on moving actors, before and after", ' ',
                     "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "The sequence's rawlog", true, "", "seq.rawlog",
                                  cmd);
  TCLAP::ValueArg<std::string> gt("", "gt", "Its ground truth (label file v1)", true, "",
                                  "seq.gt.labels", cmd);
  TCLAP::ValueArg<std::string> poses("", "poses", "Its sensor poses (TUM)", true, "", "seq.gt.tum",
                                     cmd);
  TCLAP::ValueArg<std::string> before("", "before", "Map before (points-map text: x y z a line)",
                                      true, "", "raw.txt", cmd);
  TCLAP::ValueArg<std::string> after("", "after", "Map after", true, "", "filtered.txt", cmd);
  TCLAP::ValueArg<std::string> out("o", "output", "Side-by-side top-down PNG", false, "",
                                   "maps.png", cmd);
  dynobj::apps::SensorArgs sensor(cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;

  dynobj::mrptio::RawlogFrameSource source(in.getValue(), sensor.converter(),
                                           {sensor.label(), 0, SIZE_MAX});
  const auto actors =
      dynobj::mapclean::ActorPoints::fromSequence(source, gt.getValue(), poses.getValue());
  const auto a = dynobj::mapclean::readPointsMapText(before.getValue());
  const auto b = dynobj::mapclean::readPointsMapText(after.getValue());
  const auto ca = dynobj::mapclean::countOnActors(a, actors);
  const auto cb = dynobj::mapclean::countOnActors(b, actors);
  std::printf("map points on moving actors: before %zu (of %zu), after %zu (of %zu)\n",
              ca.on_actors, ca.points, cb.on_actors, cb.points);
  if (out.isSet()) {
    char ta[96], tb[96];
    std::snprintf(ta, sizeof(ta), "before: %zu of %zu points on moving actors", ca.on_actors,
                  ca.points);
    std::snprintf(tb, sizeof(tb), "after: %zu of %zu points on moving actors", cb.on_actors,
                  cb.points);
    dynobj::io::writePngAtomically(out.getValue(),
                                   dynobj::mapclean::renderSideBySide(a, ta, b, tb, actors));
    std::printf("  -> %s\n", out.getValue().c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-mapcompare", [&] { return run(argc, argv); });
}
