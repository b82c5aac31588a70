// SPDX-License-Identifier: BSD-3-Clause
// dynobj-mapcompare: two maps of one sequence (e.g. stock icp-slam on the raw and on the filtered
// rawlog), compared label-free (how many map points the sweeps see through, each map with the
// poses that built it) and, given ground truth, by the points on the moving actors; one top-down
// PNG of both side by side with those points in red. The detector never sees the ground truth.
#include <dynobj/io/Png.h>
#include <dynobj/mapclean/MapComparison.h>
#include <dynobj/mrptio/RawlogFrameSource.h>

#include <cstdio>
#include <stdexcept>

#include "../common/AppOptions.h"

namespace {

namespace mc = dynobj::mapclean;

std::string share(std::size_t n, std::size_t of) {
  char b[64];
  std::snprintf(b, sizeof(b), "%zu of %zu (%.2f %%)", n, of, of ? 100.0 * n / of : 0.0);
  return b;
}

std::size_t count(const std::vector<bool>& v) {
  std::size_t n = 0;
  for (const bool b : v) n += b;
  return n;
}

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd(
      "dynobj-mapcompare: a map before and after a filter, label-free and against "
      "ground truth",
      ' ', "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "The sequence's rawlog (the raw one)", true, "",
                                  "seq.rawlog", cmd);
  TCLAP::ValueArg<std::string> before("", "before", "Map before (points-map text: x y z a line)",
                                      true, "", "raw.txt", cmd);
  TCLAP::ValueArg<std::string> after("", "after", "Map after", true, "", "filtered.txt", cmd);
  TCLAP::ValueArg<std::string> before_poses(
      "", "before-poses",
      "Label-free check: the poses that built the map before (the SLAM run's .simplemap, a TUM "
      "file, odometry or ego)",
      false, "", "source", cmd);
  TCLAP::ValueArg<std::string> after_poses("", "after-poses",
                                           "Label-free check: the poses that built the map after",
                                           false, "", "source", cmd);
  TCLAP::ValueArg<std::string> gt("", "gt", "Ground truth (label file v1): points on actors", false,
                                  "", "seq.gt.labels", cmd);
  TCLAP::ValueArg<std::string> poses("", "poses", "The ground truth's sensor poses (TUM)", false,
                                     "", "seq.gt.tum", cmd);
  TCLAP::ValueArg<std::string> out("o", "output", "Side-by-side top-down PNG", false, "",
                                   "maps.png", cmd);
  TCLAP::SwitchArg overwrite("w", "overwrite", "Replace an existing output PNG", cmd);
  dynobj::apps::SensorArgs sensor(cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;
  const bool truth = gt.isSet() || poses.isSet();
  const bool label_free = before_poses.isSet() || after_poses.isSet();
  if (truth && !(gt.isSet() && poses.isSet()))
    throw std::invalid_argument("--gt and --poses go together (the ground truth and its poses)");
  if (label_free && !(before_poses.isSet() && after_poses.isSet()))
    throw std::invalid_argument(
        "--before-poses and --after-poses go together (the poses that built each map)");
  if (!truth && !label_free)
    throw std::invalid_argument(
        "nothing to compare: give --before-poses and --after-poses (label-free: map points the "
        "sweeps see through), and/or --gt and --poses (map points on moving actors)");

  dynobj::apps::refuseExisting({out.getValue()}, overwrite.isSet());
  dynobj::mrptio::RawlogFrameSource source(in.getValue(), sensor.converter(),
                                           {sensor.label(), 0, SIZE_MAX});
  const auto a = mc::readPointsMapText(before.getValue());
  const auto b = mc::readPointsMapText(after.getValue());
  std::vector<bool> marked_a, marked_b;
  std::string means, caption_a, caption_b;
  if (truth) {
    const auto actors = mc::ActorPoints::fromSequence(source, gt.getValue(), poses.getValue());
    marked_a = mc::onActors(a, actors);
    marked_b = mc::onActors(b, actors);
    std::printf("map points on moving actors: before %zu (of %zu), after %zu (of %zu)\n",
                count(marked_a), a.size(), count(marked_b), b.size());
    means = "on a moving actor (ground truth)";
  }
  if (label_free) {
    std::string used_a, used_b;
    const auto through_a = mc::seenThrough(a, source, before_poses.getValue(), {}, &used_a);
    const auto through_b = mc::seenThrough(b, source, after_poses.getValue(), {}, &used_b);
    std::printf(
        "map points the sweeps see through (label-free): before %s, after %s\n"
        "  poses: before %s; after %s\n",
        share(count(through_a), a.size()).c_str(), share(count(through_b), b.size()).c_str(),
        used_a.c_str(), used_b.c_str());
    if (!truth) {
      marked_a = through_a;
      marked_b = through_b;
      means = "seen through by the sweeps";
    }
  }
  if (out.isSet()) {
    caption_a = "before: " + share(count(marked_a), a.size()) + " " + means;
    caption_b = "after: " + share(count(marked_b), b.size()) + " " + means;
    dynobj::io::writePngAtomically(
        out.getValue(),
        mc::renderSideBySide(a, marked_a, caption_a, b, marked_b, caption_b, means));
    std::printf("  -> %s\n", out.getValue().c_str());
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-mapcompare", [&] { return run(argc, argv); });
}
