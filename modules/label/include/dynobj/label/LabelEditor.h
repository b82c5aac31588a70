// SPDX-License-Identifier: BSD-3-Clause
// The state of one labelling session (dynobj-label): per sweep, which pixels belong to which
// object, whether each label was confirmed by a person or only proposed (propagated, or the
// detector's pre-label), and which sweeps a person reviewed. Region growing from a clicked pixel
// (the detector's core::RegionGrower over a ground mask from core::GroundSegmenter), propagation of
// an object to the next sweep (ego-motion + the object's velocity, then grown again), saving as
// label file v1 + instance file (with the `# reviewed` line) + a session file, and resuming.
// Not thread-safe: the server serialises calls.
#pragma once

#include <dynobj/core/EgoMotionEstimator.h>
#include <dynobj/core/GroundSegmenter.h>
#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/Params.h>
#include <dynobj/core/RegionGrower.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <list>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynobj/label/SweepSource.h"

namespace dynobj::label {

/// A request the session cannot carry out (no return at the clicked pixel, unknown object, a
/// label file for another sensor, ...); what() is meant for the user.
class LabelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LabelParams : public core::StageParams {
  double distance = 0.25;      ///< [m] region growing: epsilon between neighbouring points (the
                               ///< page's slider starts here)
  double max_extent = 1.5;     ///< [m] region growing: farthest pixel from the seeds' centre
  double seed_distance = 0.3;  ///< [m] propagation: a predicted point seeds the pixel whose point
                               ///< lies within this distance of it
  int cache_sweeps = 16;       ///< sweeps kept in memory (frame + ground mask)
  bool feet = true;            ///< also take the ground pixels right below an object that
                               ///< continue it (where it stands on the floor)
  // From the detector's INI (-c), not from [label]:
  core::RegionGrowingParams growing;  ///< the rest of the detector's region growing
  core::GroundParams ground;          ///< the detector's ground segmentation
  core::EgoMotionParams ego_motion;   ///< ego-motion when the input has no odometry

  void visit(core::ParamVisitor& v) override;
  void validate() const override;
};

enum class LabelState { confirmed, proposed, prelabel };
const char* toString(LabelState s);
LabelState labelStateFromString(const std::string& s);

struct ObjectLabel {
  int id = 0;
  LabelState state = LabelState::confirmed;
  std::vector<std::uint32_t> pixels;  ///< row * cols + col, ascending
};

struct ObjectInfo {
  int id = 0;
  std::string cls = "object";  ///< free text (pedestrian, car, ...)
  bool moving = true;          ///< moving objects go to the label file; all to the instance file
};

struct SweepLabels {
  std::vector<ObjectLabel> objects;  ///< ordered by id
  bool reviewed = false;
};

/// A sweep as the session uses it.
struct LoadedSweep {
  core::LidarFrame frame;
  std::optional<Eigen::Isometry3d> pose;  ///< sensor pose in the odometry frame, if known
  cv::Mat_<std::uint8_t> ground;          ///< 255 = ground
};

struct Propagation {
  std::size_t to = 0;                 ///< the sweep it went to
  bool found = false;                 ///< false: nothing matched the prediction (occluded, gone)
  bool kept = false;                  ///< the target already had a confirmed label: kept as is
  std::size_t pixels = 0;             ///< size of the label in `to`
  Eigen::Vector3d velocity{0, 0, 0};  ///< [m/s] the object's estimated velocity (sensor frame)
  std::string ego_motion;             ///< "odometry", "intensity", "none"
};

class LabelEditor {
 public:
  LabelEditor(SweepSource& source, const LabelParams& params);

  std::size_t size() const { return labels_.size(); }
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  std::int64_t timestamp(std::size_t k) const { return source_.timestamp(k); }
  const LabelParams& params() const { return p_; }
  /// Changes counter: every modification increments it (autosave compares it).
  std::uint64_t revision() const { return revision_; }

  /// Sweep k with its ground mask (cached; at most cache_sweeps kept). Throws LabelError when
  /// the sweep cannot be read or has another size than sweep 0.
  std::shared_ptr<const LoadedSweep> sweep(std::size_t k);

  /// Region growing from pixel (row, col) of sweep k (snapped to the nearest non-ground return
  /// within 1 row / 3 columns), never into ground or pixels of other objects than `id` (-1: any
  /// object is blocked). `distance` / `max_extent` <= 0: the session's. Returns the pixels;
  /// throws LabelError when there is no return to start from.
  std::vector<std::uint32_t> grow(std::size_t k, int row, int col, int id = -1, double distance = 0,
                                  double max_extent = 0);

  /// Sets object `id`'s pixels in sweep k (empty = removes it from k); its pixels leave any other
  /// object of k. A proposal (`state` != confirmed) makes the sweep unreviewed.
  void setObject(std::size_t k, int id, std::vector<std::uint32_t> pixels,
                 LabelState state = LabelState::confirmed);
  const SweepLabels& labels(std::size_t k) const { return labels_.at(k); }
  const ObjectLabel* object(std::size_t k, int id) const;

  /// A new object id (and its info entry).
  int newObject(const std::string& cls = "object", bool moving = true);
  const std::map<int, ObjectInfo>& objects() const { return info_; }
  void setObjectInfo(const ObjectInfo& info);

  /// Carries object `id` from sweep k to k + 1: its points moved by its velocity (from its label
  /// in k - 1, if any) and the ego-motion (odometry, else ORB on the intensity images), then
  /// grown there. Stored as a proposal unless k + 1 already has a confirmed label of `id`.
  Propagation propagate(std::size_t k, int id);

  /// Marks sweep k reviewed (its labels become confirmed) or not.
  void setReviewed(std::size_t k, bool reviewed);
  std::size_t reviewedCount() const;
  /// Sweeps holding at least one label.
  std::size_t labelledCount() const;

  /// Adds a detector's label file (v1, same size and timestamps) as pre-labels: per sweep that
  /// has no label yet, each 8-connected group of dynamic pixels becomes an object, state
  /// prelabel. Returns the number of objects added. Throws LabelError on a mismatch.
  std::size_t loadPrelabels(const std::string& labels_file);

  /// Writes <base>.labels (moving objects), <base>.instances (all objects, their ids) and
  /// <base>.session.json (object classes, states) atomically. Throws std::runtime_error naming
  /// the file on an I/O error; the session's state is unchanged either way.
  void save(const std::string& base, const std::string& rawlog = "") const;
  /// Resumes from save()'s files. Throws LabelError when they do not fit this input (another
  /// sensor size, other sweeps) or cannot be read.
  void load(const std::string& base);
  /// The files save() writes for `base`.
  static std::vector<std::string> outputFiles(const std::string& base);

 private:
  SweepLabels& mutableLabels(std::size_t k);
  Eigen::Isometry3d motion(std::size_t from, std::size_t to, std::string& source);
  /// 255 on the pixels of sweep k's objects other than `except_id`.
  cv::Mat_<std::uint8_t> others(std::size_t k, int except_id) const;

  SweepSource& source_;
  LabelParams p_;
  int rows_ = 0, cols_ = 0;
  std::vector<SweepLabels> labels_;
  std::map<int, ObjectInfo> info_;
  int next_id_ = 1;
  std::uint64_t revision_ = 0;
  std::list<std::pair<std::size_t, std::shared_ptr<LoadedSweep>>> cache_;  ///< most recent first
  core::GroundSegmenter ground_;
};

}  // namespace dynobj::label
