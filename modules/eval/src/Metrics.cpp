// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/Metrics.h"

namespace dynobj::eval {
namespace {

std::optional<double> ratio(std::int64_t num, std::int64_t den) {
  if (den == 0) return std::nullopt;
  return static_cast<double>(num) / static_cast<double>(den);
}

}  // namespace

void Confusion::add(const cv::Mat_<std::uint8_t>& predicted, const cv::Mat_<std::uint8_t>& truth,
                    const cv::Mat_<std::uint8_t>& valid) {
  CV_Assert(predicted.size() == truth.size() && truth.size() == valid.size());
  for (int r = 0; r < valid.rows; r++) {
    const std::uint8_t* p = predicted.ptr<std::uint8_t>(r);
    const std::uint8_t* t = truth.ptr<std::uint8_t>(r);
    const std::uint8_t* v = valid.ptr<std::uint8_t>(r);
    for (int c = 0; c < valid.cols; c++) {
      if (!v[c]) continue;
      const bool pp = p[c] != 0, tt = t[c] != 0;
      tp += pp && tt;
      fp += pp && !tt;
      fn += !pp && tt;
      tn += !pp && !tt;
    }
  }
}

Confusion& Confusion::operator+=(const Confusion& o) {
  tp += o.tp;
  fp += o.fp;
  fn += o.fn;
  tn += o.tn;
  return *this;
}

std::optional<double> Confusion::precision() const {
  return ratio(tp, tp + fp);
}
std::optional<double> Confusion::recall() const {
  return ratio(tp, tp + fn);
}
std::optional<double> Confusion::iou() const {
  return ratio(tp, tp + fp + fn);
}
std::optional<double> Confusion::f1() const {
  return ratio(2 * tp, 2 * tp + fp + fn);
}
std::optional<double> Confusion::falsePositiveRate() const {
  return ratio(fp, fp + tn);
}

}  // namespace dynobj::eval
