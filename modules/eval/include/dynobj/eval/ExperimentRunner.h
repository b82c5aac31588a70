// SPDX-License-Identifier: BSD-3-Clause
// Runs one configuration over a labelled sequence and scores it sweep by sweep: this detector
// with its own intensity ego-motion (the product), with ground-truth ego-motion (an upper bound),
// with drifting odometry injected, or MRPT's CPointCloudFilterByDistance (the baseline that ships
// with MRPT), all fed the same frames.
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>

#include <cstddef>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "dynobj/eval/DriftModel.h"
#include "dynobj/eval/RunResult.h"

namespace dynobj::eval {

/// The files of a labelled sequence <dir>/<name>.* (as dynobj-sim writes them).
struct SequenceFiles {
  std::string name, rawlog, labels, instances, objects, poses;
  /// prepare() from a scenario: whether it simulated the sequence or reused one (for the user).
  std::string note;

  /// `path`: a sequence folder (holding exactly one *.rawlog) or the .rawlog itself. The rawlog
  /// and <name>.gt.labels must exist; the others are optional ("" when absent).
  static SequenceFiles locate(const std::string& path);

  /// `input` a scenario (.yaml): simulated into <out_dir>/<name>/ (`frames` > 0 overrides the
  /// scenario's count), reused only when <name>.sim-stamp there matches the scenario's text, seed,
  /// frames and the simulator's fingerprint (its first sweep), else simulated again; anything
  /// else: locate(input).
  static SequenceFiles prepare(const std::string& input, const std::string& out_dir,
                               const std::string& share_dir, int frames = 0);
};

struct RunOptions {
  std::string mode = "intensity";  ///< intensity | gt-ego | drift | mrpt-distance
  core::DetectorParams params;
  DriftParams drift;
  std::string sensor_label;      ///< empty: every LiDAR observation
  std::set<int> overlay_sweeps;  ///< sweep indices to draw
  int min_object_points = 10;    ///< object-level recall: smaller objects are not counted
  std::size_t max_frames = std::numeric_limits<std::size_t>::max();
  std::function<void(std::size_t)> progress;  ///< called after each frame (may be empty)

  static const std::set<std::string>& modes();
  static std::string describe(const std::string& mode, const DriftParams& drift);
  /// "a,b,..." -> modes, checked; empty: all four with ground-truth poses, else "intensity".
  /// Throws std::invalid_argument naming an unknown one.
  static std::vector<std::string> parseModes(const std::string& list, bool have_poses);
  /// `count` evenly spaced sweeps of `frames` (skipping the first window, where nothing can be
  /// flagged yet).
  static std::set<int> evenlySpacedSweeps(int count, std::size_t frames);
  /// "i,j,..." -> sweep indices in [0, frames); throws std::invalid_argument naming a bad one.
  static std::set<int> parseSweeps(const std::string& list, std::size_t frames);
};

/// Throws EvaluationError (mismatched ground truth, missing poses) or the readers' errors.
RunResult runExperiment(const SequenceFiles& seq, const RunOptions& opts);

}  // namespace dynobj::eval
