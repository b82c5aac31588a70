// SPDX-License-Identifier: BSD-3-Clause
// dynobj-detect: runs the detector over the LiDAR scans of a rawlog, writes the dynamic pixels in
// the dynamic-label file format v1, and (given ground truth) prints the paper's metrics.
#include <dynobj/eval/DetectionDiagnostics.h>
#include <dynobj/eval/EgoMotionCheck.h>
#include <dynobj/eval/EgoMotionError.h>
#include <dynobj/eval/MapConsistency.h>
#include <dynobj/eval/Overlay.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/io/Png.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/OpenFrameSource.h>
#include <dynobj/mrptio/SequenceRunner.h>

#include <cstdio>
#include <iostream>
#include <memory>

#include "../common/AppOptions.h"

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-detect: detect dynamic points in a rawlog's LiDAR scans", ' ', "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "Input rawlog, or a folder of .pcd / .bin sweeps",
                                  true, "", "input", cmd);
  const dynobj::apps::OutputArg out(cmd, "Write the detections (label file v1)", false,
                                    "file.labels", "labels-out");
  TCLAP::ValueArg<std::string> gt("", "gt",
                                  "Ground-truth label file: print precision/recall/IoU/F1", false,
                                  "", "file.labels", cmd);
  TCLAP::ValueArg<std::string> poses(
      "", "poses",
      "TUM file of sensor poses: use them as ego-motion instead of the "
      "intensity ego-motion (e.g. ground truth)",
      false, "", "file.tum", cmd);
  TCLAP::ValueArg<std::string> ego_truth(
      "", "ego-truth",
      "TUM file of true sensor poses: print the ego-motion's error against them (not used by the "
      "detector)",
      false, "", "file.tum", cmd);
  TCLAP::ValueArg<std::string> config("c", "config", "Detector parameters (INI)", false, "",
                                      "file.ini", cmd);
  TCLAP::SwitchArg check_ego("", "check-ego",
                             "Also register consecutive frames with MRPT's 3D ICP and print how "
                             "often the ego-motion agrees with it (no ground truth needed)",
                             cmd);
  dynobj::apps::SensorArgs sensor(cmd);
  TCLAP::ValueArg<std::string> overlays(
      "", "overlay-dir",
      "Write intensity images with dynamic pixels in red (with --gt: true positives red, false "
      "positives yellow, misses blue)",
      false, "", "dir", cmd);
  TCLAP::ValueArg<std::string> consistency(
      "", "consistency",
      "Label-free check against the whole sequence (no ground truth): print how many flagged "
      "points lie where the other sweeps see a static surface, and write a top view (PNG)",
      false, "", "map.png", cmd);
  TCLAP::ValueArg<std::string> poses_out(
      "", "poses-out",
      "Write the detector's ego-motion, chained from the first sweep (its sensor pose = "
      "identity), as a TUM file of sensor poses",
      false, "", "file.tum", cmd);
  TCLAP::SwitchArg verbose("v", "verbose", "One line per frame", cmd);
  TCLAP::SwitchArg overwrite("w", "overwrite", "Replace existing output files", cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output (only the summary)", cmd);
  const dynobj::apps::ThreadsArg threads(cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;

  dynobj::apps::refuseExisting({out.getValue(), poses_out.getValue(), consistency.getValue()},
                               overwrite.isSet());
  dynobj::mrptio::SequenceOptions so;
  so.detector = dynobj::apps::loadDetectorParams(config.getValue());
  threads.apply(so.detector);
  if (poses.isSet() && ego_truth.isSet())
    throw std::invalid_argument(
        "give --poses (used as motion) or --ego-truth (compared), not both");
  so.poses = ego_truth.isSet() ? ego_truth.getValue() : poses.getValue();
  so.poses_as_motion = !ego_truth.isSet();
  so.ground_truth = gt.getValue();
  so.single_sensor =
      out.isSet() || consistency.isSet() || ego_truth.isSet() || poses_out.isSet();  // one sensor
  std::optional<dynobj::apps::OutputFolder> overlay_dir;
  if (overlays.isSet()) overlay_dir.emplace(overlays.getValue());
  dynobj::mrptio::OpenedFrameSource opened =  // a rawlog, or a folder of PCD / .bin sweeps
      dynobj::mrptio::openFrameSource(in.getValue(), sensor.model(), sensor.label());
  dynobj::mrptio::FrameSource& source = *opened.source;
  std::optional<dynobj::eval::EgoMotionCheck> ego_check;
  if (check_ego.isSet()) ego_check.emplace();
  std::optional<dynobj::eval::MapConsistency> map_check;
  if (consistency.isSet()) map_check.emplace();
  std::optional<Eigen::Isometry3d> sensor_pose;  // accumulated ego-motion
  dynobj::eval::EgoMotionError ego_error;
  std::optional<Eigen::Isometry3d> last_truth;
  std::unique_ptr<dynobj::io::LabelFileWriter> writer;
  std::optional<dynobj::io::TumWriter> pose_writer;
  if (poses_out.isSet())
    pose_writer.emplace(poses_out.getValue(), "dynobj-detect ego-motion of " + in.getValue());
  dynobj::eval::DetectionDiagnostics diag;
  dynobj::mrptio::SequenceRunner(source, so).run([&](const dynobj::mrptio::FrameResult& fr) {
    const auto& f = fr.frame.frame;
    const auto& r = *fr.detection;
    if (!writer && out.isSet())
      writer = std::make_unique<dynobj::io::LabelFileWriter>(out.getValue(), f.rows(), f.cols());
    if (writer) writer->write(f.timestamp_ns, dynobj::io::pixelsOfMask(r.dynamic));
    if (ego_check) ego_check->add(f, r.ego_motion);
    if (ego_truth.isSet()) {
      if (last_truth) ego_error.add(last_truth->inverse() * fr.pose->pose, r.ego_motion.motion);
      last_truth = fr.pose->pose;
    }
    sensor_pose = sensor_pose ? *sensor_pose * r.ego_motion.motion : Eigen::Isometry3d::Identity();
    if (map_check) map_check->add(f, *sensor_pose, r.dynamic);
    if (pose_writer) pose_writer->write(f.timestamp_ns, *sensor_pose);
    const cv::Mat_<std::uint8_t> truth = fr.truthMask();
    const auto c = diag.add(f, r, truth);
    std::cerr << dynobj::eval::DetectionDiagnostics::warningLines("dynobj-detect", fr.frame.where,
                                                                  r);
    if (overlays.isSet()) {
      char name[64];
      std::snprintf(name, sizeof(name), "/frame_%06zu.png", fr.frame.index);
      dynobj::io::writePng(overlays.getValue() + name,
                           dynobj::eval::overlayImage(f, r.dynamic, truth, r.objects));
    }
    if (verbose.isSet())
      std::cout << dynobj::eval::DetectionDiagnostics::frameLine(fr.frame.index, r, c);
  });
  if (writer) writer->close();
  if (pose_writer) pose_writer->close();
  std::cout << diag.summaryLine() << diag.faultsLine();
  diag.timing().print(std::cout);
  if (ego_check) std::cout << "  ICP check: " << ego_check->summary().toString() << "\n";
  if (ego_truth.isSet()) std::cout << "  " << ego_error.toString() << "\n";
  if (map_check) {
    std::cout << "  consistency: " << map_check->evaluate().toString() << "\n";
    dynobj::io::writePng(consistency.getValue(), map_check->topView());
  }
  std::cout << diag.metricsLines();
  if (overlay_dir) overlay_dir->keep();
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-detect", [&] { return run(argc, argv); });
}
