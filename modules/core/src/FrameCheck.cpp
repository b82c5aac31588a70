// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/FrameCheck.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "dynobj/core/Config.h"

namespace dynobj::core {
namespace {

/// A gap of this many sweep periods or more (up to max_gap) is reported as missing sweeps.
constexpr double kMissingPeriods = 1.5;
/// More returns per pixel than the sweep before by this share: the sweep holds more than 360
/// degrees (0.1 = 36 degrees of the revolution twice).
constexpr double kWideShare = 0.1;

/// `v` with `decimals` decimals.
std::string fixed(double v, int decimals) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.*f", decimals, v);
  return buf;
}

/// Input points mapped to a pixel per valid pixel; 0 when the frame keeps no point map.
double returnsPerPixel(const LidarFrame& f) {
  if (f.point_pixel.empty()) return 0;
  const std::size_t valid = f.validCount();
  if (valid == 0) return 0;
  const auto mapped = static_cast<std::size_t>(std::count_if(
      f.point_pixel.begin(), f.point_pixel.end(), [](std::int32_t p) { return p >= 0; }));
  return static_cast<double>(mapped) / static_cast<double>(valid);
}

bool sameRanges(const cv::Mat_<float>& a, const cv::Mat_<float>& b) {
  if (a.size() != b.size() || a.empty()) return false;
  if (a.isContinuous() && b.isContinuous())
    return std::memcmp(a.ptr(0), b.ptr(0), a.total() * sizeof(float)) == 0;
  return cv::norm(a, b, cv::NORM_INF) == 0;
}

/// The longest run of set entries of a 1 x n row, going round (the columns close a revolution).
int longestRun(const cv::Mat_<std::uint8_t>& row) {
  const int n = row.cols;
  int best = 0, run = 0;
  for (int i = 0; i < 2 * n && best < n; i++) {
    run = row(0, i % n) ? run + 1 : 0;
    best = std::max(best, std::min(run, n));
  }
  return best;
}

}  // namespace

const char* toString(FrameFault f) {
  switch (f) {
    case FrameFault::TimeReversal:
      return "time reversal";
    case FrameFault::DuplicateTime:
      return "duplicate timestamp";
    case FrameFault::DuplicateContent:
      return "duplicate sweep";
    case FrameFault::TimeJump:
      return "time jump";
    case FrameFault::MissingSweeps:
      return "missing sweeps";
    case FrameFault::LostColumns:
      return "partial or blocked sweep";
    case FrameFault::WideSweep:
      return "sweep over 360 degrees";
    case FrameFault::ZeroIntensity:
      return "zero intensity";
    case FrameFault::EgoMotionFailures:
      return "ego-motion failures";
  }
  return "?";
}

std::string faultCounts(const std::map<FrameFault, std::size_t>& counts) {
  std::string s;
  for (const auto& [fault, n] : counts)
    s += (s.empty() ? "" : ", ") + std::to_string(n) + " " + toString(fault);
  return s;
}

std::string FrameWarning::text() const {
  return "sweep " + std::to_string(sweep) + ": " + message;
}

void FrameCheckParams::visit(ParamVisitor& v) {
  v.value("max_gap", max_gap, kPositive);
  v.value("max_lost_columns", max_lost_columns, {0.01, 1.0});
  v.value("max_ego_failures", max_ego_failures, {1, 1000000});
}

FrameCheck::FrameCheck(const FrameCheckParams& p) : p_(p) {
  p_.validate();
}

void FrameCheck::reset() {
  have_prev_ = false;
  prev_stamp_ = 0;
  prev_range_.release();
  prev_columns_.release();
  prev_returns_per_pixel_ = 0;
  prev_intensity_ = false;
  ego_failures_ = 0;
}

FrameCheck::Verdict FrameCheck::check(const LidarFrame& f, long sweep,
                                      std::vector<FrameWarning>& out) {
  const auto warn = [&](FrameFault fault, double figure, std::string message) {
    out.push_back(FrameWarning{fault, sweep, figure, std::move(message)});
  };
  const double returns_per_pixel = returnsPerPixel(f);
  const bool intensity = f.has_intensity && cv::countNonZero(f.intensity) > 0;
  cv::Mat_<std::uint8_t> columns;  // 255 where the column has a return
  cv::reduce(f.valid, columns, 0, cv::REDUCE_MAX);
  if (!have_prev_) {
    remember(f, columns, returns_per_pixel, intensity);
    return Verdict::Use;
  }
  // Time: only between two stamped sweeps (0 = no time).
  Verdict verdict = Verdict::Use;
  if (f.timestamp_ns != 0 && prev_stamp_ != 0) {
    const double dt = 1e-9 * static_cast<double>(f.timestamp_ns - prev_stamp_);
    const double period = 1.0 / f.sensor.frequency;
    if (std::abs(dt) > p_.max_gap) {  // the clock jumped, ahead or back: start anew from here
      warn(FrameFault::TimeJump, dt,
           (dt > 0 ? "a gap of " : "time went back ") + fixed(std::abs(dt), 3) +
               " s (more than max_gap " + fixed(p_.max_gap, 3) +
               " s): the tracks and the motion history start anew");
      verdict = Verdict::Restart;
    } else if (dt < 0) {  // a sweep out of order: after a step back, at most max_gap of them
      warn(FrameFault::TimeReversal, -dt,
           "time went back " + fixed(-dt, 3) + " s: the sweep is not used for tracking");
      return Verdict::Skip;
    } else if (dt == 0) {
      warn(FrameFault::DuplicateTime, 0,
           "the same timestamp as the sweep before: the sweep is not used for tracking");
      return Verdict::Skip;
    } else if (dt >= kMissingPeriods * period) {
      warn(FrameFault::MissingSweeps, dt,
           "a gap of " + fixed(dt, 3) + " s: about " + fixed(std::round(dt / period) - 1, 0) +
               " sweeps of " + fixed(period, 3) + " s missing");
    }
  }
  if (f.validCount() > 0 && sameRanges(f.range, prev_range_)) {
    warn(FrameFault::DuplicateContent, 0,
         "the same ranges as the sweep before: the sweep is not used for tracking");
    if (f.timestamp_ns != 0) prev_stamp_ = f.timestamp_ns;  // its time is right: a stale sensor
    return Verdict::Skip;                                   // is not a time jump a second later
  }
  // Columns that had a return in the sweep before and have none now.
  if (prev_columns_.size() == columns.size()) {
    const cv::Mat_<std::uint8_t> lost = prev_columns_ & ~columns;
    const int had = cv::countNonZero(prev_columns_), gone = cv::countNonZero(lost);
    const double share = had > 0 ? static_cast<double>(gone) / had : 0.0;
    if (share > p_.max_lost_columns)
      warn(FrameFault::LostColumns, share,
           fixed(100.0 * share, 0) + " % of the columns lost their returns (the widest gap " +
               fixed(360.0 * longestRun(lost) / columns.cols, 0) +
               " deg): a partial or blocked sweep");
  }
  // More input points per pixel than the sweep before: part of the revolution is there twice.
  if (returns_per_pixel > 0 && prev_returns_per_pixel_ > 0 &&
      returns_per_pixel > (1 + kWideShare) * prev_returns_per_pixel_) {
    const double extra = 360.0 * (returns_per_pixel / prev_returns_per_pixel_ - 1);
    warn(FrameFault::WideSweep, extra,
         fixed(returns_per_pixel, 2) + " returns per pixel after " +
             fixed(prev_returns_per_pixel_, 2) + ": the sweep holds about " + fixed(extra, 0) +
             " deg more than a revolution");
  }
  if (f.has_intensity && !intensity && prev_intensity_ && f.validCount() > 0)
    warn(FrameFault::ZeroIntensity, 0,
         "every return's intensity is 0 (the sweep before had intensity): no features");
  remember(f, columns, returns_per_pixel, intensity);
  return verdict;
}

void FrameCheck::remember(const LidarFrame& f, const cv::Mat_<std::uint8_t>& columns,
                          double returns_per_pixel, bool intensity) {
  have_prev_ = true;
  prev_stamp_ = f.timestamp_ns;
  f.range.copyTo(prev_range_);
  columns.copyTo(prev_columns_);
  prev_returns_per_pixel_ = returns_per_pixel;
  prev_intensity_ = intensity;
}

void FrameCheck::egoMotion(bool ok, long sweep, std::vector<FrameWarning>& out) {
  ego_failures_ = ok ? 0 : ego_failures_ + 1;
  if (ego_failures_ == p_.max_ego_failures)
    out.push_back(
        FrameWarning{FrameFault::EgoMotionFailures, sweep, static_cast<double>(ego_failures_),
                     "the ego-motion failed on " + std::to_string(ego_failures_) +
                         " sweeps in a row: no track's movement is judged until it is back"});
}

}  // namespace dynobj::core
