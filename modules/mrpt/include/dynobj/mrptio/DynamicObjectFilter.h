// SPDX-License-Identifier: BSD-3-Clause
// The MRPT observation filter, for MRPT chains that hand over one observation at a time
// (rawlog-dynobj, icp-slam-dynobj, your own app): one detector per sensor label (DetectorBank),
// fed observations in time order, tagging each supported LiDAR observation in place
// (docs/formats.md §4, "Dynamic tags"):
//   mark    - labels only (CObservation3DRangeScan pixelLabels bit "dynamic");
//   drop    - mark + the dynamic points removed from what stock map insertion reads (default);
//   split   - drop + the removed points as a CObservationPointCloud "<label>_DYNAMIC" after it;
//   restore - undoes drop (no detection).
// Non-LiDAR observations pass through untouched; a LiDAR observation that cannot be processed
// passes through untouched too, with a warning counted in the summary.
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/mrptio/DetectorBank.h"
#include "dynobj/mrptio/ObservationConverter.h"

namespace dynobj::mrptio {

enum class FilterMode { Mark, Drop, Split, Restore };

/// "mark", "drop", "split", "restore"; throws std::invalid_argument listing them.
FilterMode parseFilterMode(const std::string& name);
const char* toString(FilterMode m);

struct FilterSummary {
  std::size_t observations = 0;    ///< every observation seen
  std::size_t lidar = 0;           ///< LiDAR observations processed (tagged)
  std::size_t points = 0;          ///< their points
  std::size_t dynamic_points = 0;  ///< of which dynamic (flagged, removed or restored)
  std::size_t passed_through = 0;  ///< LiDAR observations left untouched (see warnings)
  std::map<std::string, std::size_t> warnings;  ///< message -> count
  /// Faults of the data (core::FrameCheck) of the LiDAR observations tagged, in tagging order:
  /// (sensor label, warning).
  std::vector<std::pair<std::string, core::FrameWarning>> data_faults;
  double detector_ms = 0;  ///< total detector time
  /// Every observation seen, by "'<label>' (<class>)" -> count: what a run that filtered nothing
  /// found instead.
  std::map<std::string, std::size_t> seen;

  /// Adds the counts, times, warnings, data faults and observations seen of `other`.
  FilterSummary& operator+=(const FilterSummary& other);
  /// data_faults by fault, for summaries (core::faultCounts).
  std::map<core::FrameFault, std::size_t> faultCounts() const;
  /// Counts `obs` in `seen`.
  void see(const mrpt::obs::CObservation& obs);
  /// The error of a run that filtered no LiDAR frame (of `sensor_label`, when not empty): the
  /// sensor labels and observation classes it found, and why LiDAR ones passed through.
  std::string nothingFiltered(const std::string& sensor_label) const;
};

/// An observation converted ahead of filter(), by another thread (the pipelined rawlog filter
/// converts in its reader thread while a lane detects the previous frame): the frame, or the
/// conversion's error message.
struct PreconvertedFrame {
  core::LidarFrame frame;
  bool ok = false;
  std::string error;  ///< ConversionError's message when !ok
};

class DynamicObjectFilter {
 public:
  struct Options {
    FilterMode mode = FilterMode::Drop;
    std::string sensor_label;                 ///< only this label; empty = every LiDAR observation
    std::optional<core::SensorModel> sensor;  ///< geometry for point clouds / rotating scans
    core::DetectorParams detector;
  };

  explicit DynamicObjectFilter(Options opts);

  /// Filters one observation in place. In split mode the removed points are appended to `extra`
  /// (when given). Returns this observation's detection, or nullptr when it was not processed.
  /// `pre`: the observation already converted by preconvert() (of a filter with the same
  /// options, fed the same observations in the same order); its frame is taken over.
  const core::DetectionResult* filter(const mrpt::obs::CObservation::Ptr& obs,
                                      std::vector<mrpt::obs::CObservation::Ptr>* extra = nullptr,
                                      PreconvertedFrame* pre = nullptr);
  /// filter() in two steps, for callers that hold a frame's result before tagging it (the rawlog
  /// filter's hindsight lag): detect() counts, converts (or takes `pre`'s frame, left there)
  /// and detects; the result is valid until the next call and nullptr when the observation is
  /// not processed (counted as filter() would). tag() then tags `obs` with a result (possibly
  /// revised since) of its `frame` and counts the points.
  const core::DetectionResult* detect(const mrpt::obs::CObservation::Ptr& obs,
                                      PreconvertedFrame* pre = nullptr);
  void tag(const mrpt::obs::CObservation::Ptr& obs, const core::LidarFrame& frame,
           const core::DetectionResult& result,
           std::vector<mrpt::obs::CObservation::Ptr>* extra = nullptr);
  /// Whether filter() would convert this observation (a handled LiDAR observation that the mode
  /// does not pass through unconverted). Has no side effect.
  bool converts(const mrpt::obs::CObservation& obs) const;
  /// filter()'s conversion step alone, for an observation that converts(): the frame or the
  /// error into `out`. Uses (and advances) this filter's converter: one thread only.
  void preconvert(const mrpt::obs::CObservation& obs, PreconvertedFrame& out);
  /// Whether filter() works on this observation (a LiDAR class, and the chosen label if any);
  /// for the others filter() only counts them.
  bool handles(const mrpt::obs::CObservation& obs) const;
  /// Every observation of a sensory frame; split-mode extras are inserted into it.
  void filter(mrpt::obs::CSensoryFrame& sf);

  const FilterSummary& summary() const { return summary_; }
  const Options& options() const { return opts_; }
  /// The frame of the last observation converted here (not given converted ahead).
  const core::LidarFrame& lastFrame() const { return frame_; }

 private:
  void warn(const std::string& message);

  Options opts_;
  ObservationConverter converter_;
  DetectorBank detectors_;  ///< one detector per sensor label
  core::LidarFrame frame_;
  FilterSummary summary_;
};

}  // namespace dynobj::mrptio
