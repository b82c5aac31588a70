// SPDX-License-Identifier: BSD-3-Clause
// dynobj-mapclean: builds a static map without ghost trails (and the moving objects' map) from a
// rawlog or a KTH DynamicMap folder; optional benchmark export and map-level metrics. A long
// recording in chunks: --plan-chunks, --chunk-from/--chunk-to (one process a chunk), --merge.
#include <dynobj/mapclean/ChunkMerge.h>
#include <dynobj/mapclean/MapCleanJob.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include "../common/AppOptions.h"

namespace {

namespace mc = dynobj::mapclean;

/// --chunk-to's value: seconds, or "end".
double parseTo(const std::string& v) {
  if (v == "end") return std::numeric_limits<double>::infinity();
  std::size_t used = 0;
  double s = std::nan("");
  try {
    s = std::stod(v, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != v.size() || !std::isfinite(s))
    throw std::invalid_argument("--chunk-to '" + v + "': seconds since the first scan, or end");
  return s;
}

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-mapclean: a static map without the trails of moving objects", ' ',
                     "0.1");
  TCLAP::ValueArg<std::string> in("i", "input",
                                  "Input: a .rawlog, or a KTH DynamicMap folder (pcd/*.pcd)", false,
                                  "", "in", cmd);
  const dynobj::apps::OutputArg out(cmd, "Output folder (created if missing)", false, "dir",
                                    "out-dir");
  TCLAP::ValueArg<std::string> poses("", "poses",
                                     "Pose source: auto (default: odometry if the input has it, "
                                     "else viewpoint, else ego) | odometry | ego | viewpoint | "
                                     "file.tum | file.simplemap",
                                     false, "auto", "source", cmd);
  TCLAP::SwitchArg tum_robot("", "tum-robot-poses", "The TUM file holds robot (not sensor) poses",
                             cmd);
  TCLAP::ValueArg<double> pose_tol("", "pose-tolerance", "Timestamp matching tolerance [s]", false,
                                   0.001, "s", cmd);
  TCLAP::ValueArg<std::string> config(
      "c", "config",
      "INI: detector sections (as dynobj.ini) and [mapclean] (voxel_size, "
      "backfill_window, box_margin, min_range, dynamic_vote, free_space_*)",
      false, "", "file.ini", cmd);
  TCLAP::ValueArg<double> voxel("", "voxel", "Map voxel size [m] (0 = every point)", false, -1, "m",
                                cmd);
  TCLAP::SwitchArg level(
      "", "level-poses",
      "Level each pose with the scan's floor (roll, pitch, height; assumes a level floor)", cmd);
  TCLAP::SwitchArg single(
      "", "no-backfill",
      "No back-fill of confirmed tracks: map each sweep as soon as its detection is final (after "
      "the hindsight lag; [mapclean] backfill_window = 0)",
      cmd);
  dynobj::apps::SensorArgs sensor(cmd);
  TCLAP::ValueArg<std::string> labels(
      "", "labels",
      "Classify each scan's points with this label file v1 (e.g. dynobj-label's) instead of the "
      "detector",
      false, "", "file", cmd);
  TCLAP::ValueArg<std::string> gt("", "gt",
                                  "Ground truth for SA/DA/AA: label file v1, or gt_cloud.pcd",
                                  false, "", "file", cmd);
  TCLAP::ValueArg<double> tol("", "tolerance", "Metric distance [m] (KTH benchmark: 0.05)", false,
                              0.05, "m", cmd);
  TCLAP::ValueArg<std::string> kth("", "export-kth",
                                   "Also export a KTH DynamicMap folder (pcd/, gt_cloud.pcd)",
                                   false, "", "dir", cmd);
  TCLAP::ValueArg<std::string> formats(
      "", "formats",
      "Outputs besides poses.tum, comma-separated: ply (static/dynamic.ply), pointsmap "
      "(serialized CPointsMapXYZI), txt (x y z intensity), png (map.png, static.png), simplemap "
      "(cleaned.simplemap keyframes), or all",
      false, "ply,png,simplemap", "list", cmd);
  TCLAP::ValueArg<double> kf("", "keyframe-distance",
                             "Cleaned simplemap: keyframe every this many m (0 = every scan)",
                             false, 1.0, "m", cmd);
  TCLAP::ValueArg<double> from(
      "", "chunk-from",
      "A chunk of a long recording: map the scans from this time [s] "
      "since the first scan (with --chunk-to; merge the chunks with --merge)",
      false, 0, "s", cmd);
  TCLAP::ValueArg<std::string> to("", "chunk-to", "... up to this time [s] (excluded), or end",
                                  false, "end", "s|end", cmd);
  TCLAP::ValueArg<double> overlap(
      "", "chunk-overlap",
      "A chunk also reads this many seconds before and after its range (not mapped: detector "
      "warm-up, free-space views, back-fill, the poses that align the chunks)",
      false, 30, "s", cmd);
  TCLAP::ValueArg<double> plan("", "plan-chunks",
                               "Print chunks of about this many seconds of -i, one 'from to' "
                               "line each (for GNU parallel or a Slurm array), and exit",
                               false, 0, "s", cmd);
  TCLAP::SwitchArg merge("", "merge",
                         "Merge the chunk folders given after the options into -o's map", cmd);
  TCLAP::UnlabeledMultiArg<std::string> chunk_dirs("chunks", "Chunk folders (with --merge)", false,
                                                   "dir", cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);
  TCLAP::SwitchArg overwrite("w", "overwrite", "Replace the outputs of an earlier run", cmd);
  const dynobj::apps::ThreadsArg threads(cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;

  const auto usage = [](const std::string& problem) {
    std::cerr << "dynobj-mapclean: error: " << problem << " (see --help)\n";
    return 2;
  };
  const bool chunked = from.isSet() || to.isSet();
  if (merge.isSet()) {
    if (chunked || plan.isSet())
      return usage(
          "--merge takes the chunk folders and -o (and --gt, with -i for a label file), "
          "not --chunk-from, --chunk-to or --plan-chunks");
  } else {
    if (!chunk_dirs.getValue().empty())
      return usage("unexpected argument '" + chunk_dirs.getValue().front() +
                   "' (chunk folders go with --merge)");
    if (!in.isSet()) return usage("-i/--input is required");
  }
  if (!plan.isSet() && !out.isSet()) return usage("-o/--output is required");
  std::optional<mc::ChunkRange> chunk;
  if (chunked) try {
      chunk = mc::ChunkRange{from.getValue(), parseTo(to.getValue()), overlap.getValue()};
      chunk->validate();
    } catch (const std::invalid_argument& e) {
      return usage(e.what());
    }
  if (plan.isSet()) {
    if (out.isSet() || chunked)
      return usage("--plan-chunks prints the chunks of -i: no -o, --chunk-from or --chunk-to");
    mc::ScanSourceOptions scans;
    scans.sensor = sensor.model();
    scans.sensor_label = sensor.label();
    for (const auto& [a, b] : mc::planChunks(in.getValue(), scans, plan.getValue())) {
      char line[64];
      std::snprintf(line, sizeof(line), std::isfinite(b) ? "%.9g %.9g\n" : "%.9g end\n", a, b);
      std::cout << line;
    }
    return 0;
  }

  const bool tty = isatty(STDERR_FILENO) && !quiet.isSet();
  std::string last_stage;
  std::map<std::string, dynobj::apps::TimeLeft> left;  // per stage
  const auto progress = [&](const char* stage, std::size_t done, std::size_t total,
                            double fraction) {
    if (quiet.isSet()) return;
    const std::string eta = left[stage].update(fraction);
    const bool step = total ? (done % std::max<std::size_t>(1, total / 10) == 0 || done == total)
                            : done % 50 == 0;
    if (!tty && !step) return;
    if (tty && last_stage != stage && !last_stage.empty()) std::cerr << "\n";
    last_stage = stage;
    std::cerr << (tty ? "\r" : "") << "[dynobj-mapclean] " << stage << ": "
              << (std::string(stage) == "merge" ? "chunk " : "scan ") << done;
    if (total) std::cerr << "/" << total;
    if (fraction >= 0) std::cerr << ", " << static_cast<int>(100 * fraction) << " %";
    if (!eta.empty()) std::cerr << ", " << eta;
    std::cerr << (tty ? "   " : "\n") << std::flush;
  };

  if (merge.isSet()) {
    mc::MergeOptions m;
    m.chunks = chunk_dirs.getValue();
    m.out_dir = out.getValue();
    m.overwrite = overwrite.isSet();
    m.formats = mc::MapFormats::parse(formats.getValue());
    m.ground_truth = gt.getValue();
    m.input = in.getValue();
    m.scan_options.sensor = sensor.model();
    m.scan_options.sensor_label = sensor.label();
    m.tolerance = tol.getValue();
    dynobj::apps::OutputFolder folder(m.out_dir);  // removed again if the merge fails
    const auto s = mc::mergeChunks(m, progress);
    folder.keep();
    if (tty) std::cerr << "\n";
    std::cout << mc::mergeSummaryText(s, m);
    return 0;
  }

  dynobj::mapclean::MapCleanOptions o;
  o.input = in.getValue();
  o.out_dir = out.getValue();
  o.overwrite = overwrite.isSet();
  o.poses = poses.getValue();
  o.pose_options.tolerance_s = pose_tol.getValue();
  o.pose_options.tum_robot_poses = tum_robot.getValue();
  o.detector = dynobj::apps::loadDetectorParams(config.getValue(), "", {{"mapclean", &o.clean}});
  threads.apply(o.detector);
  if (voxel.isSet()) o.clean.voxel_size = voxel.getValue();
  if (single.isSet()) o.clean.backfill_window = 0;
  if (level.isSet()) o.clean.level_poses = true;
  o.clean.validate();
  o.scan_options.sensor = sensor.model();
  o.scan_options.sensor_label = sensor.label();
  o.labels = labels.getValue();
  o.ground_truth = gt.getValue();
  o.tolerance = tol.getValue();
  o.export_kth = kth.getValue();
  o.formats = dynobj::mapclean::MapFormats::parse(formats.getValue());
  o.keyframe_distance = kf.getValue();
  o.chunk = chunk;
  dynobj::apps::OutputFolder folder(o.out_dir);  // removed again if the run fails before a file
  const auto s = dynobj::mapclean::runMapClean(o, progress);
  folder.keep();
  if (tty) std::cerr << "\n";
  std::cout << dynobj::mapclean::summaryText(s, o);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-mapclean", [&] { return run(argc, argv); });
}
