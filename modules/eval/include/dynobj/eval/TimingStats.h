// SPDX-License-Identifier: BSD-3-Clause
// Per-stage timing statistics over many frames (median and 99th percentile), for benchmarks.
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>

#include <map>
#include <ostream>
#include <string>
#include <vector>

namespace dynobj::eval {

class TimingStats {
 public:
  /// Records one frame's stage timings.
  void add(const core::StageTimings& t);
  std::size_t frames() const { return frames_; }
  /// The stages, in pipeline order: "ground", "foreground", "ego-motion", "clustering",
  /// "association", "movement", "region growing", "hindsight" (offline runs), "total".
  static const std::vector<std::string>& stages();
  /// q-th percentile (0..100) of a stage's times [ms].
  double percentile(const std::string& stage, double q) const;
  /// A table "stage  median ms  p99 ms", stages in pipeline order.
  void print(std::ostream& out) const;

 private:
  std::map<std::string, std::vector<double>> ms_;
  std::size_t frames_ = 0;
};

}  // namespace dynobj::eval
