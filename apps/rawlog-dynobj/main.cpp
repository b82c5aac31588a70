// SPDX-License-Identifier: BSD-3-Clause
// rawlog-dynobj: rawlog in -> rawlog out with the moving objects' points tagged (mark) or removed
// (drop, split) or put back (restore); a link in a rawlog-edit chain. Streams entry by entry,
// keeps the rawlog format, writes <out>.partial and renames it only when everything went well
// (the work: mrptio::filterRawlog).
#include <dynobj/mrptio/RawlogFilter.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <limits>

#include "../common/AppOptions.h"

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("rawlog-dynobj: tag or remove the points of moving objects in a rawlog", ' ',
                     "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "Input rawlog", true, "", "in.rawlog", cmd);
  TCLAP::ValueArg<std::string> out("o", "output", "Output rawlog", true, "", "out.rawlog", cmd);
  TCLAP::SwitchArg overwrite("w", "overwrite", "Replace an existing output file", cmd);
  TCLAP::SwitchArg skip("", "skip-existing",
                        "Batch jobs: when every output exists already (outputs are only ever "
                        "complete), do nothing and exit 0",
                        cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);
  TCLAP::ValueArg<std::string> mode("", "mode", "mark | drop | split | restore (default: drop)",
                                    false, "drop", "mode", cmd);
  TCLAP::ValueArg<std::string> config("c", "config", "Detector parameters (INI)", false, "",
                                      "file.ini", cmd);
  TCLAP::ValueArg<std::string> section("", "section", "Prefix of the INI sections (e.g. dynobj_)",
                                       false, "", "prefix", cmd);
  TCLAP::SwitchArg online("", "online",
                          "Causal, zero latency (the paper): no hindsight lag (default: each "
                          "sweep is held for [hindsight] lag, 1 s, so that tracks confirmed later "
                          "flag their earlier sweeps, as dynobj-detect does)",
                          cmd);
  dynobj::apps::SensorArgs sensor(cmd);
  TCLAP::ValueArg<std::string> labels_out(
      "", "labels-out", "Also write the detections (label file v1)", false, "", "file.labels", cmd);
  TCLAP::ValueArg<std::string> tracks_out(
      "", "tracks-out", "Also write the tracked objects, one CSV row per frame and track", false,
      "", "file.csv", cmd);
  TCLAP::ValueArg<std::size_t> from("", "from", "First entry to filter (earlier ones are copied)",
                                    false, 0, "N", cmd);
  TCLAP::ValueArg<std::size_t> to("", "to", "Last entry to filter (later ones are copied)", false,
                                  std::numeric_limits<std::size_t>::max(), "N", cmd);
  TCLAP::ValueArg<int> level("", "compression-level",
                             "Output gzip level: 0 = plain rawlog, 1 = fastest (default) .. 3",
                             false, 1, "0-3", cmd);
  TCLAP::SwitchArg allow_none("", "allow-none",
                              "A run that filters no LiDAR frame is a plain copy, exit 0 (without "
                              "it: an error listing the labels and classes found)",
                              cmd);
  TCLAP::ValueArg<unsigned> threads("", "threads",
                                    "Threads (0 = one per core, default; 1 = read, detect and "
                                    "write one after another)",
                                    false, 0, "N", cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;

  if (skip.isSet() && overwrite.isSet()) {
    std::cerr << "rawlog-dynobj: error: --skip-existing and -w/--overwrite exclude each other\n";
    return 2;
  }
  if (skip.isSet() &&
      dynobj::apps::allExist({out.getValue(), labels_out.getValue(), tracks_out.getValue()})) {
    std::printf("rawlog-dynobj: '%s' exists: skipped\n", out.getValue().c_str());
    return 0;
  }
  dynobj::mrptio::RawlogFilterOptions o;
  try {
    o.filter.mode = dynobj::mrptio::parseFilterMode(mode.getValue());
  } catch (const std::invalid_argument& e) {
    std::cerr << "rawlog-dynobj: error: --mode: " << e.what() << "\n";
    return 2;
  }
  o.filter.sensor_label = sensor.label();
  o.filter.sensor = sensor.model();
  o.filter.detector = dynobj::apps::loadDetectorParams(config.getValue(), section.getValue());
  if (online.isSet()) o.filter.detector.hindsight.lag = 0;
  o.from = from.getValue();
  o.to = to.getValue();
  o.labels_out = labels_out.getValue();
  o.tracks_out = tracks_out.getValue();
  o.overwrite = overwrite.isSet();
  o.compression_level = level.getValue();
  o.threads = threads.getValue();
  o.allow_none = allow_none.isSet();
  const bool tty = !quiet.isSet() && isatty(STDERR_FILENO);
  const auto t0 = std::chrono::steady_clock::now();
  std::size_t faults_printed = 0;  // the data faults (FrameCheck) are printed once each, always
  o.progress = [&](std::size_t entries, const dynobj::mrptio::FilterSummary& sm) {
    for (; faults_printed < sm.data_faults.size(); faults_printed++) {
      const auto& [label, w] = sm.data_faults[faults_printed];
      std::fprintf(stderr, "%srawlog-dynobj: warning: '%s' %s\n", tty ? "\r" : "", label.c_str(),
                   w.text().c_str());
    }
    if (!tty || entries % 10 != 1) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "\r[rawlog-dynobj] entry %zu, %zu LiDAR frames, %.1f frames/s   ", entries,
                 sm.lidar, s > 0 ? static_cast<double>(sm.lidar) / s : 0.0);
  };
  const auto res = dynobj::mrptio::filterRawlog(in.getValue(), out.getValue(), o);
  if (tty) std::fprintf(stderr, "\n");
  const auto& sm = res.filter;
  std::string what = dynobj::mrptio::toString(o.filter.mode);  // "drop, offline"; "restore"
  if (o.filter.mode != dynobj::mrptio::FilterMode::Restore)
    what += o.filter.detector.hindsight.lag > 0 ? ", offline" : ", online";
  std::printf(
      "rawlog-dynobj: %zu entries, %zu observations; %zu LiDAR frames (%s): %zu points, %zu "
      "dynamic (%.2f%%); %zu passed through; %.2f ms/frame\n",
      res.entries, sm.observations, sm.lidar, what.c_str(), sm.points, sm.dynamic_points,
      sm.points ? 100.0 * static_cast<double>(sm.dynamic_points) / static_cast<double>(sm.points)
                : 0.0,
      sm.passed_through, sm.lidar ? sm.detector_ms / static_cast<double>(sm.lidar) : 0.0);
  for (const auto& [msg, n] : sm.warnings) std::printf("  warning (%zux): %s\n", n, msg.c_str());
  if (!sm.data_faults.empty())
    std::printf("  data faults: %s\n", dynobj::core::faultCounts(sm.faultCounts()).c_str());
  if (sm.lidar == 0 && sm.passed_through == 0)
    std::printf("  note: no LiDAR observation%s was found; the output is a copy of the input\n",
                sensor.labelSet() ? (" with label '" + sensor.label() + "'").c_str() : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("rawlog-dynobj", [&] { return run(argc, argv); });
}
