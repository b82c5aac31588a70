// SPDX-License-Identifier: BSD-3-Clause
// What one evaluation run (one detector configuration or baseline over one sequence) produced:
// the per-point metrics, the object-level recall, the timings and a few overlay images.
#pragma once

#include <dynobj/eval/TimingStats.h>

#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dynobj/eval/ObjectRecall.h"
#include "dynobj/eval/SequenceMetrics.h"

namespace dynobj::eval {

struct RunResult {
  std::string mode;         ///< short key: intensity, gt-ego, drift, mrpt-distance, files
  std::string description;  ///< one line for tables
  std::string sequence;     ///< sequence name
  int rows = 0, cols = 0;
  double rate_hz = 10;  ///< sensor rate: the real-time budget is 1000 / rate_hz ms
  SequenceMetrics metrics;
  std::optional<ObjectRecall> objects;  ///< when the instance and object files exist
  std::optional<TimingStats> timing;    ///< per-stage times (detector runs only)
  std::size_t ego_failed = 0;
  std::vector<std::pair<int, cv::Mat>> overlays;  ///< (sweep index, BGR image)
};

}  // namespace dynobj::eval
