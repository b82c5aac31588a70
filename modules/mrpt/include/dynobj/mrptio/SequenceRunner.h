// SPDX-License-Identifier: BSD-3-Clause
// The one sequence loop of the offline tools (dynobj-detect, dynobj-eval, dynobj-mapclean,
// dynobj-bench): frames from a FrameSource, each through its sensor's detector (DetectorBank),
// with optional external motion (a TUM file of sensor poses, matched by timestamp: the motion
// between a sensor's consecutive frames replaces the intensity ego-motion) and optional ground
// truth (label file v1, matched by timestamp, same image size), one callback per frame.
// With hindsight (DetectorParams::hindsight.lag > 0, the default) each frame is held that long
// before its callback, so that tracks confirmed later flag their earlier clusters too
// (core::Hindsight); the callbacks still come once per frame, in the source's order.
#pragma once

#include <dynobj/core/HindsightQueue.h>
#include <dynobj/io/PoseFile.h>

#include <cstddef>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/mrptio/DetectorBank.h"
#include "dynobj/mrptio/FrameSource.h"
#include "dynobj/mrptio/GroundTruth.h"

namespace dynobj::mrptio {

struct SequenceOptions {
  core::DetectorParams detector;
  bool detect = true;  ///< false: frames, poses and ground truth only (baselines of dynobj-eval)
  std::string poses;   ///< TUM file of sensor poses in the world ("" = none)
  bool poses_as_motion = true;  ///< the poses' motion is given to the detector (else: reported)
  /// Alters the external motion before the detector sees it (dynobj-eval's drifting odometry).
  std::function<Eigen::Isometry3d(const Eigen::Isometry3d&)> motion_model;
  std::string ground_truth;  ///< label file v1 ("" = none)
  /// A second sensor label is an error (implied by ground truth): outputs of one sensor.
  bool single_sensor = false;
  std::size_t max_frames = std::numeric_limits<std::size_t>::max();
  bool require_frames = true;  ///< a source without any frame is an error
};

/// What the callback gets for each frame (valid during the call only).
struct FrameResult {
  explicit FrameResult(const Frame& f) : frame(f) {}
  const Frame& frame;
  const core::DetectionResult* detection = nullptr;  ///< null when SequenceOptions::detect is off
  const io::TimedPose* pose = nullptr;               ///< the frame's pose (with `poses`)
  std::optional<Eigen::Isometry3d> motion;           ///< the external motion given to the detector
  const io::LabelSweep* truth = nullptr;             ///< the frame's ground-truth sweep
  std::size_t truth_index = 0;                       ///< its index in the label file
  /// The ground-truth sweep as a mask (empty matrix without ground truth).
  cv::Mat_<std::uint8_t> truthMask() const;
};

class SequenceRunner {
 public:
  /// Reads the pose and ground-truth files (throws naming them). `source` must outlive the runner.
  SequenceRunner(FrameSource& source, SequenceOptions opts);

  /// Runs to the end of the source (or max_frames) and returns the number of frames. Throws
  /// std::runtime_error when there was none (require_frames), a frame has no pose or ground-truth
  /// sweep, or (one sensor) a second LiDAR label shows up.
  std::size_t run(const std::function<void(const FrameResult&)>& on_frame);
  /// One step of run(), for callers that hand the frames on one at a time (the Python module's
  /// process_sequence): reads and detects the source's next frame and calls `on_frame` for each
  /// frame released by it (none while the lag holds them). At the end of the source (or
  /// max_frames) releases the frames still held and returns false (and false from then on).
  /// Throws as run() does, but not when there was no frame.
  bool step(const std::function<void(const FrameResult&)>& on_frame);
  /// Frames read so far.
  std::size_t frames() const { return frames_; }

  const std::optional<GroundTruth>& groundTruth() const { return truth_; }
  DetectorBank& detectors() { return bank_; }

 private:
  const io::TimedPose* poseOf(const Frame& f) const;
  /// What a frame waiting for its callback keeps, beside its detection.
  struct Held {
    Frame frame;
    const io::TimedPose* pose = nullptr;
    std::optional<Eigen::Isometry3d> motion;
    const io::LabelSweep* truth = nullptr;
    std::size_t truth_index = 0;
  };

  FrameSource& source_;
  SequenceOptions opts_;
  DetectorBank bank_;
  std::vector<io::TimedPose> poses_;
  std::optional<GroundTruth> truth_;
  std::map<std::string, const io::TimedPose*> last_pose_;  ///< per sensor label
  std::string first_label_;
  core::HindsightQueue<Held> held_;
  Frame frame_;  ///< the frame being read (moved into held_ when held)
  std::size_t frames_ = 0;
  bool finished_ = false;
};

}  // namespace dynobj::mrptio
