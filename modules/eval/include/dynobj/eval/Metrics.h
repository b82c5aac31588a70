// SPDX-License-Identifier: BSD-3-Clause
// Per-point confusion counts and the paper's metrics (Section IV-B): precision, recall, IoU, F1.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>

namespace dynobj::eval {

struct Confusion {
  std::int64_t tp = 0, fp = 0, fn = 0, tn = 0;

  /// Adds one sweep: `predicted` and `truth` (non-zero = dynamic), counted over `valid` pixels.
  void add(const cv::Mat_<std::uint8_t>& predicted, const cv::Mat_<std::uint8_t>& truth,
           const cv::Mat_<std::uint8_t>& valid);
  Confusion& operator+=(const Confusion& o);

  /// Undefined (nullopt) when the denominator is 0.
  std::optional<double> precision() const;
  std::optional<double> recall() const;
  std::optional<double> iou() const;
  std::optional<double> f1() const;
  /// Share of truly static points flagged dynamic.
  std::optional<double> falsePositiveRate() const;
};

}  // namespace dynobj::eval
