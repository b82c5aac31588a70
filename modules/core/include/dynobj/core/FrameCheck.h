// SPDX-License-Identifier: BSD-3-Clause
// Faults of the data, not of the file: each sweep checked against the one before it (its time,
// its ranges, its columns, its returns per pixel, its intensity) and the ego-motion's run of
// failures. Returns warnings (DetectionResult::warnings) and what the detector does with the
// sweep: use it, skip it (a time reversal or a duplicate: not used for tracking), or restart (a
// time jump: the tracks and the motion history start anew). docs/usage.md, "Faults of the data".
#pragma once

#include <cstdint>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "dynobj/core/DetectionResult.h"
#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

/// "2 time reversal, 1 duplicate sweep": counts per fault for the tools' summaries ("" = none).
std::string faultCounts(const std::map<FrameFault, std::size_t>& counts);

struct FrameCheckParams : public StageParams {
  /// [s] time ahead or back by more than this between two sweeps is a time jump: the tracks and
  /// the motion history start anew (a shorter gap of 1.5 sweep periods or more: missing sweeps, a
  /// warning; a shorter step back: the sweep is skipped)
  double max_gap = 1.0;
  /// [share 0-1] of the columns with returns in the sweep before that have none: a partial sweep
  /// or a blocked field of view (a warning)
  double max_lost_columns = 0.25;
  /// [sweeps] the ego-motion failed on this many sweeps in a row (a warning)
  int max_ego_failures = 10;

  void visit(ParamVisitor& v) override;
};

class FrameCheck {
 public:
  /// What the detector does with a sweep.
  enum class Verdict {
    Use,      ///< track it (its warnings, if any, need no action)
    Skip,     ///< a time reversal or a duplicate: not used for tracking
    Restart,  ///< a time jump: the tracks and the motion history start anew with it
  };

  explicit FrameCheck(const FrameCheckParams& p = {});

  /// Sweep `sweep` against the last sweep it did not skip; appends its warnings to `out`.
  Verdict check(const LidarFrame& frame, long sweep, std::vector<FrameWarning>& out);
  /// After the ego-motion of sweep `sweep` (`ok`: estimated, or given): one warning when the
  /// failures in a row reach max_ego_failures.
  void egoMotion(bool ok, long sweep, std::vector<FrameWarning>& out);
  void reset();

  const FrameCheckParams& params() const { return p_; }

 private:
  /// Remembers `frame` (and its figures) as the sweep before the next one.
  void remember(const LidarFrame& frame, const cv::Mat_<std::uint8_t>& columns,
                double returns_per_pixel, bool intensity);

  FrameCheckParams p_;
  bool have_prev_ = false;
  std::int64_t prev_stamp_ = 0;
  cv::Mat_<float> prev_range_;
  cv::Mat_<std::uint8_t> prev_columns_;  ///< 1 x cols: 255 where the column had a return
  double prev_returns_per_pixel_ = 0;    ///< mapped input points / valid pixels (0 = not known)
  bool prev_intensity_ = false;          ///< some return had a non-zero intensity
  int ego_failures_ = 0;                 ///< in a row, up to the last sweep
};

}  // namespace dynobj::core
