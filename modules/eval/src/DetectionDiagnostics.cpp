// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/DetectionDiagnostics.h"

#include <dynobj/core/FrameCheck.h>

#include <algorithm>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <vector>

namespace dynobj::eval {
namespace {

std::string fmt(const std::optional<double>& v) {
  if (!v) return "n/a";
  char b[32];
  std::snprintf(b, sizeof(b), "%.3f", *v);
  return b;
}

}  // namespace

Confusion DetectionDiagnostics::add(const core::LidarFrame& f, const core::DetectionResult& r,
                                    const cv::Mat_<std::uint8_t>& truth) {
  timing_.add(r.timings);
  if (!r.ego_motion.ok && frames_ > 0) ego_failed_++;
  for (const core::FrameWarning& w : r.warnings) faults_[w.fault]++;
  frames_++;
  rows_ = f.rows();
  cols_ = f.cols();
  Confusion c;
  if (truth.empty()) return c;
  truth_ = true;
  c.add(r.dynamic, truth, f.valid);
  total_ += c;
  seeds_.add(r.seeds, truth, f.valid);
  // Where do the misses come from? Missed objects vs incompletely grown ones.
  cv::Mat labels;
  const int n = cv::connectedComponents(truth, labels, 8, CV_32S);
  std::vector<char> hit(static_cast<std::size_t>(n), 0);
  for (int i = 0; i < f.rows() * f.cols(); i++)
    if (r.dynamic(i / f.cols(), i % f.cols()) && labels.at<int>(i / f.cols(), i % f.cols()) > 0)
      hit[static_cast<std::size_t>(labels.at<int>(i / f.cols(), i % f.cols()))] = 1;
  for (int i = 0; i < f.rows() * f.cols(); i++) {
    const int l = labels.at<int>(i / f.cols(), i % f.cols());
    if (l > 0 && !r.dynamic(i / f.cols(), i % f.cols()) && f.valid(i / f.cols(), i % f.cols()))
      (hit[static_cast<std::size_t>(l)] ? fn_grow_ : fn_missed_)++;
  }
  return c;
}

std::string DetectionDiagnostics::frameLine(std::size_t index, const core::DetectionResult& r,
                                            const Confusion& c) {
  char b[320];
  std::snprintf(
      b, sizeof(b),
      "frame %4zu: ego %-17s inl %4d/%4d | %5d features %3zu objects, %2d dynamic | %6d px | "
      "TP %5ld FP %5ld FN %5ld | %.2f ms\n",
      index, r.ego_motion.source.c_str(), r.ego_motion.inliers, r.ego_motion.matches,
      cv::countNonZero(r.features), r.objects.size(),
      static_cast<int>(std::count_if(r.objects.begin(), r.objects.end(),
                                     [](const auto& o) { return o.dynamic; })),
      cv::countNonZero(r.dynamic), static_cast<long>(c.tp), static_cast<long>(c.fp),
      static_cast<long>(c.fn), r.timings.total);
  return b;
}

std::string DetectionDiagnostics::summaryLine() const {
  char b[160];
  std::snprintf(b, sizeof(b), "dynobj-detect: %zu frames of %dx%d, ego-motion failed on %zu\n",
                frames_, rows_, cols_, ego_failed_);
  return b;
}

std::string DetectionDiagnostics::warningLines(const std::string& app, const std::string& where,
                                               const core::DetectionResult& r) {
  std::string lines;
  for (const core::FrameWarning& w : r.warnings)
    lines += app + ": warning: sweep " + std::to_string(w.sweep) +
             (where.empty() ? "" : " (" + where + ")") + ": " + w.message + "\n";
  return lines;
}

std::string DetectionDiagnostics::faultsLine() const {
  return faults_.empty() ? "" : "  data faults: " + core::faultCounts(faults_) + "\n";
}

std::string DetectionDiagnostics::metricsLines() const {
  if (!truth_) return "";
  char b[512];
  std::snprintf(
      b, sizeof(b),
      "  precision %s  recall %s  IoU %s  F1 %s  (TP %ld FP %ld FN %ld; static points flagged "
      "%s%%)\n"
      "  seeds (accepted clusters before region growing): precision %s, %ld points; "
      "misses: %zu in undetected objects, %zu in detected objects\n",
      fmt(total_.precision()).c_str(), fmt(total_.recall()).c_str(), fmt(total_.iou()).c_str(),
      fmt(total_.f1()).c_str(), static_cast<long>(total_.tp), static_cast<long>(total_.fp),
      static_cast<long>(total_.fn),
      total_.falsePositiveRate() ? fmt(100.0 * *total_.falsePositiveRate()).c_str() : "n/a",
      fmt(seeds_.precision()).c_str(), static_cast<long>(seeds_.tp + seeds_.fp), fn_missed_,
      fn_grow_);
  return b;
}

}  // namespace dynobj::eval
