// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/SequenceMetrics.h"

#include <algorithm>
#include <cstdio>

namespace dynobj::eval {
namespace {

/// Sorted-list intersection count.
std::size_t common(const std::vector<std::uint32_t>& a, const std::vector<std::uint32_t>& b) {
  std::size_t i = 0, j = 0, n = 0;
  while (i < a.size() && j < b.size()) {
    if (a[i] < b[j])
      i++;
    else if (b[j] < a[i])
      j++;
    else
      n++, i++, j++;
  }
  return n;
}

/// Quantile with linear interpolation between closest ranks (sorted input).
double quantile(const std::vector<double>& v, double q) {
  const double pos = q * static_cast<double>(v.size() - 1);
  const auto lo = static_cast<std::size_t>(pos);
  const std::size_t hi = std::min(lo + 1, v.size() - 1);
  return v[lo] + (pos - static_cast<double>(lo)) * (v[hi] - v[lo]);
}

}  // namespace

SequenceMetrics SequenceMetrics::compute(const io::LabelFile& truth, const io::LabelFile& pred) {
  if (truth.rows != pred.rows || truth.cols != pred.cols)
    throw EvaluationError("ground truth is " + std::to_string(truth.rows) + "x" +
                          std::to_string(truth.cols) + " but the predictions are " +
                          std::to_string(pred.rows) + "x" + std::to_string(pred.cols) +
                          " (header, line 1)");
  SequenceMetrics m;
  const std::size_t n = std::max(truth.sweeps.size(), pred.sweeps.size());
  for (std::size_t k = 0; k < n; k++) {
    if (k >= truth.sweeps.size())
      throw EvaluationError(
          "prediction sweep " + std::to_string(k) + " (line " + std::to_string(k + 2) +
          ", t = " + std::to_string(pred.sweeps[k].timestamp_ns) + " ns) has no ground truth");
    if (k >= pred.sweeps.size())
      throw EvaluationError(
          "ground-truth sweep " + std::to_string(k) + " (line " + std::to_string(k + 2) +
          ", t = " + std::to_string(truth.sweeps[k].timestamp_ns) + " ns) has no prediction");
    const auto& t = truth.sweeps[k];
    const auto& p = pred.sweeps[k];
    if (t.timestamp_ns != p.timestamp_ns)
      throw EvaluationError("sweep " + std::to_string(k) + " (line " + std::to_string(k + 2) +
                            "): ground truth at t = " + std::to_string(t.timestamp_ns) +
                            " ns, prediction at " + std::to_string(p.timestamp_ns) + " ns");
    m.add(t.timestamp_ns, t.pixels, p.pixels);
  }
  return m;
}

void SequenceMetrics::add(std::int64_t timestamp_ns, const std::vector<std::uint32_t>& truth,
                          const std::vector<std::uint32_t>& predicted, std::int64_t valid_points,
                          double ms) {
  SweepMetrics s;
  s.timestamp_ns = timestamp_ns;
  s.ms = ms;
  const auto tp = static_cast<std::int64_t>(common(truth, predicted));
  s.counts.tp = tp;
  s.counts.fp = static_cast<std::int64_t>(predicted.size()) - tp;
  s.counts.fn = static_cast<std::int64_t>(truth.size()) - tp;
  if (valid_points >= 0)
    s.counts.tn = std::max<std::int64_t>(0, valid_points - tp - s.counts.fp - s.counts.fn);
  else
    static_known = false;
  total += s.counts;
  sweeps.push_back(s);
}

void SequenceMetrics::add(std::int64_t timestamp_ns, const Confusion& counts, double ms) {
  total += counts;
  sweeps.push_back({timestamp_ns, counts, ms});
}

std::optional<double> SequenceMetrics::staticFlagged() const {
  if (!static_known || sweeps.empty()) return std::nullopt;
  return total.falsePositiveRate();
}

Distribution SequenceMetrics::distribution(Metric metric) const {
  std::vector<double> v;
  for (const auto& s : sweeps) {
    std::optional<double> x;
    switch (metric) {
      case Metric::Precision:
        x = s.counts.precision();
        break;
      case Metric::Recall:
        x = s.counts.recall();
        break;
      case Metric::IoU:
        x = s.counts.iou();
        break;
      case Metric::F1:
        x = s.counts.f1();
        break;
    }
    if (x) v.push_back(*x);
  }
  Distribution d;
  d.sweeps = v.size();
  if (v.empty()) return d;
  std::sort(v.begin(), v.end());
  d.q1 = quantile(v, 0.25);
  d.median = quantile(v, 0.5);
  d.q3 = quantile(v, 0.75);
  return d;
}

std::string formatMetric(const std::optional<double>& v) {
  if (!v) return "n/a";
  char b[32];
  std::snprintf(b, sizeof(b), "%.3f", *v);
  return b;
}

}  // namespace dynobj::eval
