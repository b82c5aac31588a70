// SPDX-License-Identifier: BSD-3-Clause
// What the detector gives for one frame (DynamicObjectDetector::process): the dynamic pixels,
// the intermediate images, the tracked objects, the ego-motion and the time per stage. Offline
// tools hold results and revise them (Hindsight, HindsightQueue).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "dynobj/core/EgoMotion.h"

namespace dynobj::core {

struct TrackedObject {
  int id = 0;
  Eigen::Vector3d centroid{0, 0, 0};  ///< sensor frame [m]
  Eigen::Vector2d velocity{0, 0};     ///< sensor frame [m/s]
  Eigen::Vector3d box_min{0, 0, 0}, box_max{0, 0, 0};
  int points = 0;  ///< pixels of the object this frame (grown when dynamic)
  bool dynamic = false;
  bool at_rest = false;  ///< its track is at rest (Track::atRest): settled or clearly stopped
  int age = 0;           ///< frames since first seen
  bool filled =
      false;  ///< added by hindsight where its track was not seen (fill_gaps, fill_before)
  std::vector<int> cluster;  ///< its cluster's pixels this frame (row * cols + col)
};

struct StageTimings {
  double foreground = 0, ego_motion = 0, clustering = 0, association = 0, movement = 0, ground = 0,
         region_growing = 0, hindsight = 0, total = 0;  ///< [ms]; hindsight: offline runs
  // Each stage's own time. With [pipeline] threads = 2 the ego-motion runs while the ground,
  // foreground and clustering stages do: the total (wall time) is then less than their sum.
};

/// A fault of a sweep's data that FrameCheck found (docs/usage.md, "Faults of the data").
enum class FrameFault {
  TimeReversal,      ///< older than the sweep before (by max_gap at most): not used
  DuplicateTime,     ///< the same timestamp as the sweep before: not used
  DuplicateContent,  ///< the same ranges as the sweep before: not used
  TimeJump,       ///< time ahead or back by more than [frame_check] max_gap: tracks and motion anew
  MissingSweeps,  ///< a gap of 1.5 sweep periods or more, up to max_gap
  LostColumns,    ///< columns without returns that had them: a partial or blocked sweep
  WideSweep,      ///< more returns per pixel than the sweep before: more than 360 degrees
  ZeroIntensity,  ///< every return's intensity 0, after a sweep with intensity
  EgoMotionFailures  ///< the ego-motion failed on max_ego_failures sweeps in a row
};

/// "time reversal", "duplicate timestamp", ... (the summaries' names).
const char* toString(FrameFault f);

struct FrameWarning {
  FrameFault fault = FrameFault::TimeReversal;
  long sweep = 0;       ///< the detector's sweep number (0-based; every sweep given to process())
  double figure = 0;    ///< the figure that triggered it, in the unit `message` names
  std::string message;  ///< e.g. "time went back 0.300 s: the sweep is not used"

  /// "sweep <sweep>: <message>".
  std::string text() const;
};

struct DetectionResult {
  std::int64_t timestamp_ns = 0;
  long frame_index = 0;
  cv::Mat_<std::uint8_t> dynamic;      ///< 255 = dynamic pixel
  cv::Mat_<std::uint8_t> features;     ///< foreground feature pixels (Eq. 4), for inspection
  cv::Mat_<std::uint8_t> seeds;        ///< points of the accepted clusters (region-growing seeds)
  cv::Mat_<std::uint8_t> ground;       ///< 255 = ground pixel (region growing never enters it)
  std::vector<TrackedObject> objects;  ///< tracks seen this frame
  /// pixels region growing refused (past_surface_check: the lookback frame saw a surface there
  /// and the mover was elsewhere); hindsight's growth keeps them out too
  std::vector<int> seen_static;
  EgoMotion ego_motion;
  StageTimings timings;
  /// What FrameCheck found wrong with this sweep's data; empty on clean data.
  std::vector<FrameWarning> warnings;

  /// A copy that shares no pixel data with this one (the detector reuses its images).
  DetectionResult clone() const;
};

}  // namespace dynobj::core
