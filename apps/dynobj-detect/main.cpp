// SPDX-License-Identifier: BSD-3-Clause
// dynobj-detect: runs the detector over the LiDAR scans of a rawlog, writes the dynamic pixels in
// the dynamic-label file format v1, and (given ground truth) prints the paper's metrics.
#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/core/FrameImages.h>
#include <dynobj/core/LabelFile.h>
#include <dynobj/core/Metrics.h>
#include <dynobj/core/TimingStats.h>
#include <dynobj/core/TumFile.h>
#include <dynobj/eval/EgoMotionCheck.h>
#include <dynobj/eval/MapConsistency.h>
#include <dynobj/mrpt/LidarObservationStream.h>
#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <opencv2/imgproc.hpp>

#include "../common/AppMain.h"

namespace {

using dynobj::core::StageTimings;

std::string fmt(const std::optional<double>& v) {
  if (!v) return "n/a";
  char b[32];
  std::snprintf(b, sizeof(b), "%.3f", *v);
  return b;
}

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-detect: detect dynamic points in a rawlog's LiDAR scans", ' ', "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "Input rawlog", true, "", "file.rawlog", cmd);
  TCLAP::ValueArg<std::string> out("o", "labels-out", "Write the detections (label file v1)", false,
                                   "", "file.labels", cmd);
  TCLAP::ValueArg<std::string> gt("", "gt",
                                  "Ground-truth label file: print precision/recall/IoU/F1", false,
                                  "", "file.labels", cmd);
  TCLAP::ValueArg<std::string> poses(
      "", "poses",
      "TUM file of sensor poses: use them as ego-motion instead of the "
      "intensity ego-motion (e.g. ground truth)",
      false, "", "file.tum", cmd);
  TCLAP::ValueArg<std::string> config("c", "config", "Detector parameters (INI)", false, "",
                                      "file.ini", cmd);
  TCLAP::SwitchArg check_ego("", "check-ego",
                            "Also register consecutive frames with MRPT's 3D ICP and print how "
                            "often the ego-motion agrees with it (no ground truth needed)",
                            cmd);
  TCLAP::ValueArg<std::string> sensor(
      "", "sensor", "Sensor preset INI (point clouds, rotating scans)", false, "", "file.ini", cmd);
  TCLAP::ValueArg<std::string> label("", "sensor-label", "Only this sensor label", false, "",
                                     "label", cmd);
  TCLAP::ValueArg<std::string> overlays("", "overlay-dir",
                                        "Write intensity images with dynamic pixels in red", false,
                                        "", "dir", cmd);
  TCLAP::ValueArg<std::string> consistency(
      "", "consistency",
      "Label-free check against the whole sequence (no ground truth): print how many flagged "
      "points lie where the other sweeps see a static surface, and write a top view (PNG)",
      false, "", "map.png", cmd);
  TCLAP::SwitchArg verbose("v", "verbose", "One line per frame", cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;

  dynobj::core::DetectorParams params;
  if (config.isSet()) {
    ::mrpt::config::CConfigFile cfg(config.getValue());
    params.load(cfg);
  }
  std::optional<dynobj::core::SensorModel> model;
  if (sensor.isSet()) model = dynobj::core::SensorModel::fromFile(sensor.getValue());
  std::optional<dynobj::core::LabelFile> truth;
  if (gt.isSet()) truth = dynobj::core::LabelFile::read(gt.getValue());
  std::vector<dynobj::core::StampedPose> trajectory;
  if (poses.isSet()) trajectory = dynobj::core::readTumFile(poses.getValue());
  if (overlays.isSet()) dynobj::apps::ensureDirectory(overlays.getValue());

  dynobj::mrpt::LidarObservationStream stream(
      in.getValue(), dynobj::mrpt::ObservationConverter(model),
      {label.getValue(), 0, std::numeric_limits<std::size_t>::max()});
  dynobj::core::DynamicObjectDetector detector(params);
  std::optional<dynobj::eval::EgoMotionCheck> ego_check;
  if (check_ego.isSet()) ego_check.emplace();
  std::optional<dynobj::eval::MapConsistency> map_check;
  if (consistency.isSet()) map_check.emplace();
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();  // accumulated ego-motion
  std::unique_ptr<dynobj::core::LabelFileWriter> writer;
  dynobj::mrpt::LidarObservationStream::Item item;
  dynobj::core::Confusion total, seeds_total;
  dynobj::core::TimingStats timing;
  std::size_t frames = 0, ego_failed = 0, truth_pos = 0, fn_grow = 0, fn_missed = 0;
  const dynobj::core::StampedPose* prev_pose = nullptr;
  while (stream.next(item)) {
    const auto& f = item.frame;
    std::optional<Eigen::Isometry3d> motion;
    if (!trajectory.empty()) {
      const auto* p = dynobj::core::findPose(trajectory, f.timestamp_ns);
      if (!p)
        throw std::runtime_error("no pose in '" + poses.getValue() + "' for frame at " +
                                 std::to_string(f.timestamp_ns) + " ns");
      if (prev_pose) motion = prev_pose->pose.inverse() * p->pose;
      prev_pose = p;
    }
    const auto& r = detector.process(f, motion);
    if (!writer && out.isSet())
      writer = std::make_unique<dynobj::core::LabelFileWriter>(out.getValue(), f.rows(), f.cols());
    if (writer) writer->write(f.timestamp_ns, dynobj::core::pixelsOfMask(r.dynamic));
    const StageTimings& t = r.timings;
    timing.add(t);
    if (!r.ego_motion.ok && frames > 0) ego_failed++;
    if (ego_check) ego_check->add(f, r.ego_motion);
    if (map_check) {
      if (frames > 0) sensor_pose = sensor_pose * r.ego_motion.motion;
      map_check->add(f, sensor_pose, r.dynamic);
    }
    dynobj::core::Confusion c;
    if (truth) {
      if (frames >= truth->sweeps.size() || truth->sweeps[frames].timestamp_ns != f.timestamp_ns)
        throw std::runtime_error("ground truth has no sweep at " + std::to_string(f.timestamp_ns) +
                                 " ns (frame " + std::to_string(frames) + ")");
      if (truth->rows != f.rows() || truth->cols != f.cols())
        throw std::runtime_error("ground truth is " + std::to_string(truth->rows) + "x" +
                                 std::to_string(truth->cols) + " but the scans are " +
                                 std::to_string(f.rows()) + "x" + std::to_string(f.cols()));
      cv::Mat_<std::uint8_t> gt_mask(f.rows(), f.cols(), std::uint8_t{0});
      for (auto px : truth->sweeps[frames].pixels)
        gt_mask(static_cast<int>(px) / f.cols(), static_cast<int>(px) % f.cols()) = 255;
      truth_pos += truth->sweeps[frames].pixels.size();
      c.add(r.dynamic, gt_mask, f.valid);
      total += c;
      seeds_total.add(r.seeds, gt_mask, f.valid);
      {  // where do the misses come from? missed objects vs incompletely grown ones
        cv::Mat labels;
        const int n = cv::connectedComponents(gt_mask, labels, 8, CV_32S);
        std::vector<char> hit(static_cast<std::size_t>(n), 0);
        for (int i = 0; i < f.rows() * f.cols(); i++)
          if (r.dynamic(i / f.cols(), i % f.cols()) &&
              labels.at<int>(i / f.cols(), i % f.cols()) > 0)
            hit[static_cast<std::size_t>(labels.at<int>(i / f.cols(), i % f.cols()))] = 1;
        for (int i = 0; i < f.rows() * f.cols(); i++) {
          const int l = labels.at<int>(i / f.cols(), i % f.cols());
          if (l > 0 && !r.dynamic(i / f.cols(), i % f.cols()) &&
              f.valid(i / f.cols(), i % f.cols()))
            (hit[static_cast<std::size_t>(l)] ? fn_grow : fn_missed)++;
        }
      }
      if (overlays.isSet()) {
        cv::Mat img = dynobj::core::overlayMask(dynobj::core::intensityToU8(f), r.dynamic & gt_mask,
                                                {0, 0, 255});
        img.setTo(cv::Scalar(0, 255, 255), r.dynamic & ~gt_mask);
        img.setTo(cv::Scalar(255, 0, 0), gt_mask & ~r.dynamic);
        char name[64];
        std::snprintf(name, sizeof(name), "/frame_%06zu.png", frames);
        dynobj::core::writePng(overlays.getValue() + name, dynobj::core::scaleRows(img, 2));
      }
    }
    if (verbose.isSet())
      std::printf(
          "frame %4zu: ego %-17s inl %4d/%4d | %5d features %3zu objects, %2d dynamic | %6d px | "
          "TP %5ld FP %5ld FN %5ld | %.2f ms\n",
          frames, r.ego_motion.source.c_str(), r.ego_motion.inliers, r.ego_motion.matches,
          cv::countNonZero(r.features), r.objects.size(),
          static_cast<int>(std::count_if(r.objects.begin(), r.objects.end(),
                                         [](const auto& o) { return o.dynamic; })),
          cv::countNonZero(r.dynamic), static_cast<long>(c.tp), static_cast<long>(c.fp),
          static_cast<long>(c.fn), t.total);
    frames++;
  }
  if (frames == 0) throw std::runtime_error("no LiDAR observation in '" + in.getValue() + "'");
  if (writer) writer->close();
  std::printf("dynobj-detect: %zu frames of %dx%d, ego-motion failed on %zu\n", frames,
              item.frame.rows(), item.frame.cols(), ego_failed);
  std::fflush(stdout);
  timing.print(std::cout);
  std::cout.flush();
  if (ego_check) std::printf("  ICP check: %s\n", ego_check->summary().toString().c_str());
  if (map_check) {
    std::printf("  consistency: %s\n", map_check->evaluate().toString().c_str());
    dynobj::core::writePng(consistency.getValue(), map_check->topView());
  }
  if (truth)
    std::printf(
        "  precision %s  recall %s  IoU %s  F1 %s  (TP %ld FP %ld FN %ld; static points flagged "
        "%s%%)\n",
        fmt(total.precision()).c_str(), fmt(total.recall()).c_str(), fmt(total.iou()).c_str(),
        fmt(total.f1()).c_str(), static_cast<long>(total.tp), static_cast<long>(total.fp),
        static_cast<long>(total.fn),
        total.falsePositiveRate() ? fmt(100.0 * *total.falsePositiveRate()).c_str() : "n/a");
  if (truth)
    std::printf(
        "  seeds (accepted clusters before region growing): precision %s, %ld points; "
        "misses: %zu in undetected objects, %zu in detected objects\n",
        fmt(seeds_total.precision()).c_str(), static_cast<long>(seeds_total.tp + seeds_total.fp),
        fn_missed, fn_grow);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-detect", [&] { return run(argc, argv); });
}
