// SPDX-License-Identifier: BSD-3-Clause
// Scores the detector point by point against human labels of a real recording (PointTruth.h):
// every input point of every sweep (a folder of PCD / .bin sweeps keeps all of them; a rawlog
// gives one point per pixel), in two modes over the same frames —
//   online:  causal, zero latency (the paper; what icp-slam-dynobj and rawlog-dynobj --online do),
//   offline: each sweep held for the hindsight lag (dynobj-detect, rawlog-dynobj, mapclean) —
// with per-point precision / recall / IoU / F1 over the points the truth knows (unknown points
// are left out) and object recall per class. Box tracks judge their motion from the sensor poses:
// a poses file, or else the detector's own ego-motion of the first run.
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/mrptio/FrameSource.h>

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "dynobj/eval/PointTruth.h"
#include "dynobj/eval/RunResult.h"

namespace dynobj::eval {

struct PointEvalOptions {
  core::DetectorParams params;
  std::vector<std::string> modes{"online", "offline"};
  int min_object_points = 10;  ///< object recall counts objects with this many points in a sweep
  /// Sensor poses (TUM or KITTI 3x4, one per sweep or by time) to judge box motion; empty = the
  /// detector's ego-motion.
  std::string truth_poses;
  std::string predictions_dir;  ///< <dir>/<mode>/NNNNNN.label: SemanticKITTI 9 / 251 per point
  std::string truth_dir;        ///< <dir>/NNNNNN.label: the truth as SemanticKITTI labels
  std::size_t max_frames = std::numeric_limits<std::size_t>::max();
  std::function<void(const std::string& mode, std::size_t frame)> progress;
};

/// One moving object in one sweep, as a mode saw it.
struct ObjectSighting {
  std::string mode;
  std::size_t sweep = 0;
  int object = 0;
  std::string cls;
  std::int64_t points = 0, flagged = 0;
  double range = 0;  ///< [m] horizontal distance of its points' centroid from the sensor
};

/// What a point evaluation found, beside the runs.
struct PointEvaluation {
  std::vector<RunResult> runs;            ///< one per mode
  std::vector<ObjectSighting> sightings;  ///< every moving object in every sweep, per mode
  std::vector<TrackMotion> tracks;        ///< box tracks: their judged motion (empty otherwise)
  std::size_t sweeps = 0, points = 0, known_points = 0, moving_points = 0;
};

/// `mode`: "online" or "offline"; throws std::invalid_argument for another.
std::string describePointMode(const std::string& mode);

/// "online,offline" -> the modes, checked (std::invalid_argument naming an unknown one).
std::vector<std::string> parsePointModes(const std::string& list);

/// Runs each mode over `source` (rewound before each) and scores it against `truth`. Throws
/// EvaluationError when the truth does not fit the recording.
PointEvaluation evaluatePoints(mrptio::FrameSource& source, PointTruthSource& truth,
                               const PointEvalOptions& opts);

/// The sightings as CSV (mode,sweep,object,class,points,flagged,range), to find the misses.
std::string sightingsCsv(const std::vector<ObjectSighting>& sightings);

/// The tracks' judged motion as CSV (track,class,sweeps,first,last,max_speed,moving,static,
/// unknown), for a hand check of the truth.
std::string trackMotionCsv(const std::vector<TrackMotion>& tracks);

}  // namespace dynobj::eval
