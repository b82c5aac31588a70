// SPDX-License-Identifier: BSD-3-Clause
// dynobj-eval: scores dynamic-point detections against ground truth and writes a report
// (Markdown table on stdout, per-sweep CSV, JSON, self-contained HTML with plots and overlays).
//   --run <scenario.yaml | sequence dir | file.rawlog>: simulate if needed, run the detector and
//         the baselines, evaluate, report.
//   --gt <file.labels> --pred <file.labels>: evaluate existing label files.
#include <dynobj/core/FrameImages.h>
#include <dynobj/eval/ExperimentRunner.h>
#include <dynobj/eval/Overlay.h>
#include <dynobj/eval/Report.h>
#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/io/Png.h>
#include <mrpt/config/CConfigFile.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "../common/AppMain.h"

namespace {

using namespace dynobj;

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string commandLine(int argc, char** argv) {
  std::string c = "dynobj-eval";
  for (int i = 1; i < argc; i++) c += std::string(" ") + argv[i];
  return c;
}

/// Evenly spaced sweep indices (skipping the first window, where nothing can be flagged yet).
std::set<int> overlaySweeps(int count, std::size_t frames) {
  std::set<int> out;
  const int first = std::min<int>(10, static_cast<int>(frames) - 1);
  for (int i = 0; i < count; i++)
    out.insert(first + static_cast<int>((static_cast<double>(i) + 0.5) / count *
                                        (static_cast<double>(frames) - first)));
  return out;
}

void writeOutputs(const std::string& dir, const std::string& title, const std::string& command,
                  const std::vector<eval::RunResult>& runs) {
  const std::string table = eval::markdownTable(runs);
  std::cout << table;
  io::writeFileAtomically(dir + "/summary.md", table);
  eval::writeJsonSummary(dir + "/summary.json", runs);
  std::vector<std::pair<std::string, cv::Mat>> sheet;
  for (const auto& r : runs) {
    eval::writeSweepCsv(dir + "/" + r.sequence + "." + r.mode + ".sweeps.csv", r);
    for (const auto& [sweep, img] : r.overlays) {
      char name[32];
      std::snprintf(name, sizeof(name), ".sweep-%04d.png", sweep);
      io::writePng(dir + "/overlays/" + r.sequence + "." + r.mode + name, img);
      sheet.emplace_back(r.sequence + " " + r.mode + ", sweep " + std::to_string(sweep), img);
    }
  }
  if (!sheet.empty()) io::writePng(dir + "/overlays/contact-sheet.png", eval::contactSheet(sheet));
  eval::writeHtmlReport(dir + "/report.html", title, command, runs);
  std::cerr << "[dynobj-eval] report: " << dir << "/report.html (and summary.md, summary.json, "
            << "*.sweeps.csv, overlays/)\n";
}

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-eval: evaluate dynamic-point detections and write a report", ' ',
                     "0.1");
  TCLAP::ValueArg<std::string> run_in("", "run",
                                      "Scenario (.yaml), sequence folder or .rawlog to simulate "
                                      "(if needed), detect and evaluate",
                                      false, "", "input", cmd);
  TCLAP::ValueArg<std::string> gt("", "gt", "Ground-truth label file (with --pred)", false, "",
                                  "file.labels", cmd);
  TCLAP::ValueArg<std::string> pred("", "pred", "Predicted label file (with --gt)", false, "",
                                    "file.labels", cmd);
  TCLAP::ValueArg<std::string> out("o", "out", "Report folder", true, "", "dir", cmd);
  TCLAP::ValueArg<std::string> modes("", "modes",
                                     "Comma-separated: intensity, gt-ego, drift, mrpt-distance "
                                     "(default: all four when ground-truth poses exist)",
                                     false, "", "list", cmd);
  TCLAP::ValueArg<int> frames("n", "frames", "Evaluate only the first N sweeps (and simulate N)",
                              false, 0, "N", cmd);
  TCLAP::ValueArg<std::string> config("c", "config", "Detector parameters (INI)", false, "",
                                      "file.ini", cmd);
  TCLAP::ValueArg<std::string> label("", "sensor-label", "Only this sensor label", false, "",
                                     "label", cmd);
  TCLAP::ValueArg<std::string> drift("", "drift",
                                     "Drift of the injected odometry: sigma_xy, sigma_yaw_deg, "
                                     "bias_scale, bias_yaw_deg, seed (e.g. bias_yaw_deg=0.1)",
                                     false, "", "k=v,...", cmd);
  TCLAP::ValueArg<int> overlays("", "overlays", "Overlay images per run (evenly spaced sweeps)",
                                false, 3, "N", cmd);
  TCLAP::ValueArg<std::string> overlay_list("", "overlay-sweeps",
                                            "Overlay images of these sweeps (instead of "
                                            "--overlays)",
                                            false, "", "i,j,...", cmd);
  TCLAP::ValueArg<int> min_points("", "min-object-points",
                                  "Object recall counts objects with at least this "
                                  "many points in a sweep",
                                  false, 10, "N", cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);
  if (const auto stop = apps::parseCommandLine(cmd, argc, argv)) return *stop;
  if (run_in.isSet() == (gt.isSet() || pred.isSet()) || gt.isSet() != pred.isSet()) {
    std::cerr << "dynobj-eval: error: give either --run <input>, or both --gt and --pred\n";
    return 2;
  }
  apps::ensureDirectory(out.getValue());
  apps::ensureDirectory(out.getValue() + "/overlays");
  const std::string command = commandLine(argc, argv);

  if (gt.isSet()) {  // existing files: metrics only (no frames, so no overlays or timings)
    eval::RunResult r;
    r.mode = "files";
    r.description = std::filesystem::path(pred.getValue()).filename().string();
    r.sequence = std::filesystem::path(gt.getValue()).filename().string();
    r.sequence = r.sequence.substr(0, r.sequence.find('.'));  // hall.gt.labels -> hall
    const io::LabelFile truth = io::LabelFile::read(gt.getValue());
    const io::LabelFile predicted = io::LabelFile::read(pred.getValue());
    r.metrics = eval::SequenceMetrics::compute(truth, predicted);
    r.rows = truth.rows;
    r.cols = truth.cols;
    writeOutputs(out.getValue(), "dynobj-eval: " + pred.getValue(), command, {r});
    return 0;
  }

  eval::RunOptions opts;
  if (config.isSet()) {
    mrpt::config::CConfigFile cfg(config.getValue());
    opts.params.load(cfg);
  }
  if (drift.isSet()) opts.drift = eval::DriftParams::parse(drift.getValue());
  opts.sensor_label = label.getValue();
  opts.min_object_points = min_points.getValue();
  if (frames.getValue() > 0) opts.max_frames = static_cast<std::size_t>(frames.getValue());
  const eval::SequenceFiles seq = eval::SequenceFiles::prepare(run_in.getValue(), out.getValue(),
                                                               apps::shareDir(), frames.getValue());
  std::vector<std::string> mode_list = splitList(modes.getValue());
  if (mode_list.empty())
    mode_list = seq.poses.empty()
                    ? std::vector<std::string>{"intensity"}
                    : std::vector<std::string>{"intensity", "gt-ego", "drift", "mrpt-distance"};
  for (const auto& m : mode_list)
    if (!eval::RunOptions::modes().count(m))
      throw std::invalid_argument("--modes: unknown mode '" + m +
                                  "' (intensity, gt-ego, drift, mrpt-distance)");
  const std::size_t n_sweeps =
      std::min(opts.max_frames, io::LabelFile::read(seq.labels).sweeps.size());
  opts.overlay_sweeps = overlaySweeps(std::max(0, overlays.getValue()), n_sweeps);
  if (overlay_list.isSet()) {
    opts.overlay_sweeps.clear();
    for (const auto& item : splitList(overlay_list.getValue())) {
      std::size_t used = 0;
      int k = -1;
      try {
        k = std::stoi(item, &used);
      } catch (const std::exception&) {
      }
      if (used != item.size() || k < 0 || static_cast<std::size_t>(k) >= n_sweeps)
        throw std::invalid_argument("--overlay-sweeps: '" + item +
                                    "' is not a sweep index in [0, " +
                                    std::to_string(n_sweeps - 1) + "]");
      opts.overlay_sweeps.insert(k);
    }
  }

  std::vector<eval::RunResult> runs;
  const bool tty = isatty(STDERR_FILENO) != 0;
  for (const auto& m : mode_list) {
    opts.mode = m;
    opts.progress = [&](std::size_t k) {
      if (quiet.isSet()) return;
      if (tty)
        std::cerr << "\r[dynobj-eval] " << seq.name << " " << m << ": sweep " << k << "/"
                  << n_sweeps << std::flush;
      else if (k % std::max<std::size_t>(1, n_sweeps / 4) == 0)
        std::cerr << "[dynobj-eval] " << seq.name << " " << m << ": sweep " << k << "/" << n_sweeps
                  << "\n";
    };
    runs.push_back(eval::runExperiment(seq, opts));
    if (tty && !quiet.isSet()) std::cerr << "\n";
  }
  writeOutputs(out.getValue(), "dynobj-eval: " + seq.name, command, runs);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-eval", [&] { return run(argc, argv); });
}
