// SPDX-License-Identifier: BSD-3-Clause
// dynobj-eval: scores dynamic-point detections against ground truth and writes a report
// (Markdown table on stdout, per-sweep CSV, JSON, self-contained HTML with plots and overlays).
//   --run <scenario.yaml | sequence dir | file.rawlog>: simulate if needed, run the detector and
//         the baselines, evaluate, report.
//   --gt <file.labels> --pred <file.labels>: evaluate existing label files.
//   --run <folder of sweeps | file.rawlog> --truth <human labels>: a real recording, point by
//         point, online and offline (eval/PointEvaluation.h).
#include <dynobj/eval/ExperimentRunner.h>
#include <dynobj/eval/PointEvaluation.h>
#include <dynobj/eval/ReportFolder.h>
#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/mrptio/OpenFrameSource.h>
#include <unistd.h>

#include <filesystem>
#include <iostream>

#include "../common/AppOptions.h"

namespace {

using namespace dynobj;

std::string commandLine(int argc, char** argv) {
  std::string c = "dynobj-eval";
  for (int i = 1; i < argc; i++) c += std::string(" ") + argv[i];
  return c;
}

void writeOutputs(const std::string& dir, const std::string& title, const std::string& command,
                  const std::vector<eval::RunResult>& runs) {
  std::cout << eval::writeReportFolder(dir, title, command, runs);
  std::cerr << "[dynobj-eval] report: " << dir << "/report.html (and summary.md, summary.json, "
            << "*.sweeps.csv, overlays/)\n";
}

/// Progress on stderr: a rewritten line on a terminal, a few lines otherwise.
std::function<void(const std::string&, std::size_t)> progressPrinter(const std::string& name,
                                                                     std::size_t total,
                                                                     bool quiet) {
  const bool tty = isatty(STDERR_FILENO) != 0;
  return [=](const std::string& mode, std::size_t k) {
    if (quiet) return;
    if (tty)
      std::cerr << "\r[dynobj-eval] " << name << " " << mode << ": sweep " << k << "/" << total
                << (k == total ? "\n" : "") << std::flush;
    else if (k % std::max<std::size_t>(1, total / 4) == 0)
      std::cerr << "[dynobj-eval] " << name << " " << mode << ": sweep " << k << "/" << total
                << "\n";
  };
}

/// --truth: a real recording scored point by point against human labels.
void runAgainstTruth(const std::string& input, const std::string& truth_path,
                     const std::string& calib, eval::PointEvalOptions opts,
                     const apps::SensorArgs& sensor, const std::string& label,
                     const std::string& out, const std::string& command, bool quiet) {
  mrptio::OpenedFrameSource in = mrptio::openFrameSource(input, sensor.model(), label);
  const std::unique_ptr<eval::PointTruthSource> truth = eval::openPointTruth(truth_path, calib);
  const std::string name = std::filesystem::path(input).filename().string();
  opts.progress = progressPrinter(name, std::min(in.frames, opts.max_frames), quiet);
  eval::PointEvaluation e = eval::evaluatePoints(*in.source, *truth, opts);
  for (auto& r : e.runs) r.sequence = name;
  std::cerr << "[dynobj-eval] truth: " << truth->describe() << ": " << e.sweeps << " sweeps, "
            << e.points << " points, " << e.known_points << " scored (" << e.moving_points
            << " moving), " << e.points - e.known_points << " unknown (left out)\n";
  writeOutputs(out, "dynobj-eval: " + name, command, e.runs);
  io::writeFileAtomically(out + "/objects.csv", eval::sightingsCsv(e.sightings));
  if (!e.tracks.empty()) {
    io::writeFileAtomically(out + "/truth-tracks.csv", eval::trackMotionCsv(e.tracks));
    std::cerr << "[dynobj-eval] the tracks' judged motion: " << out << "/truth-tracks.csv\n";
  }
}

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-eval: evaluate dynamic-point detections and write a report", ' ',
                     "0.1");
  TCLAP::ValueArg<std::string> run_in("i", "run",
                                      "Scenario (.yaml), sequence folder or .rawlog to simulate "
                                      "(if needed), detect and evaluate",
                                      false, "", "input", cmd);
  TCLAP::ValueArg<std::string> gt("", "gt", "Ground-truth label file (with --pred)", false, "",
                                  "file.labels", cmd);
  TCLAP::ValueArg<std::string> pred("", "pred", "Predicted label file (with --gt)", false, "",
                                    "file.labels", cmd);
  const apps::OutputArg out(cmd, "Report folder", true, "dir", "out");
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
  TCLAP::ValueArg<std::string> unreviewed(
      "", "unreviewed",
      "With --gt: sweeps of a person-made label file nobody reviewed (dynobj-label's '# "
      "reviewed' line): refuse (default), skip them, or include them as they are",
      false, "refuse", "refuse|skip|include", cmd);
  TCLAP::ValueArg<std::string> truth(
      "", "truth",
      "Human labels of the --run recording, scored point by point online and offline: KITTI "
      "tracking label_02 file (with --calib), a box-track .csv, or a folder of SemanticKITTI "
      ".label files",
      false, "", "labels", cmd);
  TCLAP::ValueArg<std::string> calib("", "calib", "KITTI calibration of --truth", false, "",
                                     "calib.txt", cmd);
  TCLAP::ValueArg<std::string> truth_poses("", "truth-poses",
                                           "Sensor poses (TUM or KITTI) to judge the boxes' "
                                           "motion (default: the detector's ego-motion)",
                                           false, "", "poses", cmd);
  TCLAP::ValueArg<std::string> truth_out("", "truth-out",
                                         "Write the truth as SemanticKITTI labels into this folder",
                                         false, "", "dir", cmd);
  TCLAP::ValueArg<std::string> pred_out(
      "", "predictions-out",
      "Write each mode's predictions as SemanticKITTI labels (9 static, 251 moving) into "
      "<dir>/<mode>/",
      false, "", "dir", cmd);
  const apps::SensorArgs sensor(cmd, false);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);
  TCLAP::SwitchArg overwrite("w", "overwrite", "Replace the report of an earlier run", cmd);
  const apps::ThreadsArg threads(cmd);
  if (const auto stop = apps::parseCommandLine(cmd, argc, argv)) return *stop;
  if (run_in.isSet() == (gt.isSet() || pred.isSet()) || gt.isSet() != pred.isSet()) {
    std::cerr << "dynobj-eval: error: give either --run <input>, or both --gt and --pred\n";
    return 2;
  }
  const std::string& dir = out.getValue();
  apps::refuseExisting({dir + "/report.html", dir + "/summary.json", dir + "/summary.md"},
                       overwrite.isSet());
  apps::OutputFolder folder(dir), overlay_folder(dir + "/overlays");  // removed again on an error
  const std::string command = commandLine(argc, argv);

  if (truth.isSet()) {
    eval::PointEvalOptions po;
    po.params = apps::loadDetectorParams(config.getValue());
    threads.apply(po.params);
    if (modes.isSet()) po.modes = eval::parsePointModes(modes.getValue());
    po.min_object_points = min_points.getValue();
    po.truth_poses = truth_poses.getValue();
    po.truth_dir = truth_out.getValue();
    po.predictions_dir = pred_out.getValue();
    if (frames.getValue() > 0) po.max_frames = static_cast<std::size_t>(frames.getValue());
    runAgainstTruth(run_in.getValue(), truth.getValue(), calib.getValue(), po, sensor,
                    label.getValue(), dir, command, quiet.isSet());
    folder.keep(), overlay_folder.keep();
    return 0;
  }

  if (gt.isSet()) {  // existing files: metrics only (no frames, so no overlays or timings)
    writeOutputs(out.getValue(), "dynobj-eval: " + pred.getValue(), command,
                 {eval::scoreLabelFiles(gt.getValue(), pred.getValue(), unreviewed.getValue())});
    folder.keep(), overlay_folder.keep();
    return 0;
  }

  eval::RunOptions opts;
  opts.params = apps::loadDetectorParams(config.getValue());
  threads.apply(opts.params);
  if (drift.isSet()) opts.drift = eval::DriftParams::parse(drift.getValue());
  opts.sensor_label = label.getValue();
  opts.min_object_points = min_points.getValue();
  if (frames.getValue() > 0) opts.max_frames = static_cast<std::size_t>(frames.getValue());
  const eval::SequenceFiles seq = eval::SequenceFiles::prepare(run_in.getValue(), out.getValue(),
                                                               apps::shareDir(), frames.getValue());
  if (!seq.note.empty()) std::cerr << "[dynobj-eval] " << seq.note << "\n";
  const auto mode_list = eval::RunOptions::parseModes(modes.getValue(), !seq.poses.empty());
  const std::size_t n_sweeps =
      std::min(opts.max_frames, io::LabelFile::read(seq.labels).sweeps.size());
  opts.overlay_sweeps =
      overlay_list.isSet()
          ? eval::RunOptions::parseSweeps(overlay_list.getValue(), n_sweeps)
          : eval::RunOptions::evenlySpacedSweeps(std::max(0, overlays.getValue()), n_sweeps);

  std::vector<eval::RunResult> runs;
  const auto progress = progressPrinter(seq.name, n_sweeps, quiet.isSet());
  for (const auto& m : mode_list) {
    opts.mode = m;
    opts.progress = [&](std::size_t k) { progress(m, k); };
    runs.push_back(eval::runExperiment(seq, opts));
  }
  writeOutputs(out.getValue(), "dynobj-eval: " + seq.name, command, runs);
  folder.keep(), overlay_folder.keep();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-eval", [&] { return run(argc, argv); });
}
