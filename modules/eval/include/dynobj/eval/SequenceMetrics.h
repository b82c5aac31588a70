// SPDX-License-Identifier: BSD-3-Clause
// The paper's per-point metrics (Section IV-B) over a labelled sequence: ground-truth and predicted
// dynamic-label files (format v1) matched sweep by sweep by timestamp. Per sweep: TP/FP/FN and
// precision / recall / IoU / F1; over the sequence: micro (summed over all points, as the paper)
// and the per-sweep distribution (median, quartiles: the paper's box plots). A metric whose
// denominator is zero is undefined (std::nullopt, printed "n/a"), never 0 or 1.
#pragma once

#include <dynobj/eval/Metrics.h>
#include <dynobj/io/LabelFile.h>

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynobj::eval {

/// Ground truth and predictions that cannot be compared; what() says which sweep / file.
class EvaluationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SweepMetrics {
  std::int64_t timestamp_ns = 0;
  eval::Confusion counts;  ///< tp, fp, fn; tn when the sweep's valid point count is known
  double ms = -1;          ///< detector time [ms] (-1 = unknown)
};

/// Quartiles of a per-sweep metric over the sweeps where it is defined.
struct Distribution {
  std::size_t sweeps = 0;  ///< sweeps where the metric is defined
  std::optional<double> q1, median, q3;
};

struct SequenceMetrics {
  std::vector<SweepMetrics> sweeps;
  eval::Confusion total;     ///< summed over every point of every sweep (micro)
  bool static_known = true;  ///< every sweep's valid point count was given (tn is meaningful)

  /// Appends one sweep: ascending pixel lists; `valid_points` < 0 when unknown (tn then 0).
  void add(std::int64_t timestamp_ns, const std::vector<std::uint32_t>& truth,
           const std::vector<std::uint32_t>& predicted, std::int64_t valid_points = -1,
           double ms = -1);
  /// Appends one sweep's counts as they are (tn included: the static points are known).
  void add(std::int64_t timestamp_ns, const Confusion& counts, double ms = -1);
  /// Share of truly static points flagged dynamic over the sequence (n/a when unknown).
  std::optional<double> staticFlagged() const;

  /// Matches the two files sweep by sweep. Both must have the same image size and exactly the
  /// same timestamps in the same order; otherwise EvaluationError names the first mismatch.
  static SequenceMetrics compute(const io::LabelFile& truth, const io::LabelFile& predicted);

  enum class Metric { Precision, Recall, IoU, F1 };
  Distribution distribution(Metric m) const;
};

/// "0.873", or "n/a" when undefined.
std::string formatMetric(const std::optional<double>& v);

}  // namespace dynobj::eval
