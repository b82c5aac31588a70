// SPDX-License-Identifier: BSD-3-Clause
// dynobj-detect's report over a sequence: frames, ego-motion failures, stage timings and, with
// ground truth, the paper's metrics summed over all points, the seeds' precision (accepted
// clusters before region growing) and where the misses come from (objects never detected vs
// detected objects grown incompletely).
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/eval/TimingStats.h>

#include <cstddef>
#include <map>
#include <opencv2/core.hpp>
#include <string>

#include "dynobj/eval/Metrics.h"

namespace dynobj::eval {

class DetectionDiagnostics {
 public:
  /// One frame; `truth` (non-zero = dynamic) is empty without ground truth. Returns the frame's
  /// counts (all zero without ground truth).
  Confusion add(const core::LidarFrame& frame, const core::DetectionResult& r,
                const cv::Mat_<std::uint8_t>& truth);

  /// "frame    k: ego <source> inl ... | <features> features <objects> objects, ... | ms".
  static std::string frameLine(std::size_t index, const core::DetectionResult& r,
                               const Confusion& c);
  /// "dynobj-detect: N frames of HxW, ego-motion failed on K\n".
  std::string summaryLine() const;
  /// The frame's data warnings (core::FrameCheck), one line each: "<app>: warning: sweep N
  /// (<where>): <message>\n"; "" on clean data.
  static std::string warningLines(const std::string& app, const std::string& where,
                                  const core::DetectionResult& r);
  /// "  data faults: 2 time reversal, 1 duplicate sweep\n", or "" when there was none.
  std::string faultsLine() const;
  /// With ground truth: the metrics line and the seeds / misses line; else "".
  std::string metricsLines() const;

  const TimingStats& timing() const { return timing_; }
  std::size_t frames() const { return frames_; }

 private:
  TimingStats timing_;
  Confusion total_, seeds_;
  bool truth_ = false;
  int rows_ = 0, cols_ = 0;
  std::size_t frames_ = 0, ego_failed_ = 0, fn_grow_ = 0, fn_missed_ = 0;
  std::map<core::FrameFault, std::size_t> faults_;
};

}  // namespace dynobj::eval
