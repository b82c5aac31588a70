// SPDX-License-Identifier: BSD-3-Clause
// The map-cleaning logic, without MRPT observations: which points of a scan are dynamic (the
// detector's mask, plus the optional second pass), and the static / dynamic voxel maps.
//
// Second pass: the detector is causal, so a moving object's first frames (before its movement
// window has enough history) are not flagged. After the whole sequence has been seen, every track
// that was ever confirmed dynamic is known; the second pass marks the points inside that track's
// box (grown by box_margin) in each frame where it was seen, including the frames before it was
// confirmed. It uses only the detector's output, never ground truth.
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/Params.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "dynobj/mapclean/MapVisibilityCheck.h"
#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {

/// Calls fn(row, col, point) for every valid pixel of `frame` at least `min_range` away, with the
/// point in the world (placed with `sensor_pose`) and the pixel's intensity.
template <class Fn>
void forEachWorldPoint(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose,
                       double min_range, Fn&& fn) {
  const Eigen::Matrix3f R = sensor_pose.linear().cast<float>();
  const Eigen::Vector3f t = sensor_pose.translation().cast<float>();
  for (int r = 0; r < frame.rows(); r++)
    for (int c = 0; c < frame.cols(); c++) {
      if (!frame.isValid(r, c) || frame.range(r, c) < min_range) continue;
      const cv::Vec3f& s = frame.xyz(r, c);
      const Eigen::Vector3f w = R * Eigen::Vector3f(s[0], s[1], s[2]) + t;
      fn(r, c, MapPoint{w.x(), w.y(), w.z(), frame.intensity(r, c)});
    }
}

/// INI section [mapclean]; keys = field names.
struct MapCleanParams : public core::StageParams {
  double voxel_size = 0.05;  ///< [m] map voxel; 0 = keep every point
  bool second_pass = true;   ///< mark confirmed tracks' earlier frames (see above)
  double box_margin = 0.15;  ///< [m] growth of a track's box sideways and upwards (second pass)
  double min_range = 0.0;    ///< [m] points nearer than this (e.g. the robot itself) are not mapped
  /// Voxel vote (finish()): a static voxel moves to the dynamic map when it received at least
  /// this many times fewer static than dynamic points (0 = off; needs voxel_size > 0).
  double dynamic_vote = 1.0;
  /// Free-space check (MapVisibilityCheck.h) of the static map after the vote, against every
  /// free_space_stride-th scan (a further streaming pass over the input; needs voxel_size > 0).
  bool free_space_check = true;
  /// Level every pose with the scan's floor (GroundLeveler.h): roll, pitch, height from the
  /// ground plane; for planar / drifting pose sources on a level floor. Off: assumes nothing.
  bool level_poses = false;
  int free_space_stride = 2;
  /// The check's own parameters (INI keys free_space_margin, free_space_margin_rel,
  /// free_space_window, free_space_min_views, free_space_ratio; min_range is the one above).
  VisibilityParams visibility;

  /// `visibility` with this min_range.
  VisibilityParams freeSpace() const;

  void visit(core::ParamVisitor& v) override;
  void validate() const override;
};

/// A tracked object of one frame, as the second pass needs it (sensor frame box).
struct ObjectBox {
  int id = 0;
  bool dynamic = false;
  Eigen::Vector3f min{0, 0, 0}, max{0, 0, 0};
};

/// What the first pass keeps per scan: small (no points), so memory stays flat.
struct FrameRecord {
  std::int64_t timestamp_ns = 0;
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();  ///< in the world
  std::vector<std::uint32_t> dynamic_pixels;                      ///< detector output, ascending
  std::vector<ObjectBox> objects;
};

class MapCleaner {
 public:
  explicit MapCleaner(const MapCleanParams& p);

  /// First pass: keeps the record's detection and notes the tracks confirmed dynamic.
  FrameRecord record(const core::DetectionResult& r, const Eigen::Isometry3d& sensor_pose);

  /// Per-pixel dynamic mask of `frame`: the detector's pixels, plus (second pass) the pixels
  /// inside the boxes of tracks confirmed dynamic at any time.
  cv::Mat_<std::uint8_t> dynamicMask(const core::LidarFrame& frame, const FrameRecord& rec,
                                     bool second_pass) const;

  /// Adds every valid pixel of `frame` (placed with `sensor_pose`) to the static or dynamic map.
  void accumulate(const core::LidarFrame& frame, const cv::Mat_<std::uint8_t>& dynamic_mask,
                  const Eigen::Isometry3d& sensor_pose);

  /// After the last scan: applies the voxel vote. Returns the voxels moved.
  std::size_t finish();
  /// Moves the static voxels with these keys (ascending, e.g. MapVisibilityCheck::seenThrough()) to
  /// the dynamic map. Returns how many moved.
  std::size_t moveToDynamic(const std::vector<std::uint64_t>& keys);

  const VoxelMap& staticMap() const { return static_; }
  const VoxelMap& dynamicMap() const { return dynamic_; }
  const std::set<int>& confirmedTracks() const { return confirmed_; }
  std::size_t backfilledPixels() const { return backfilled_; }
  const MapCleanParams& params() const { return p_; }

 private:
  MapCleanParams p_;
  std::set<int> confirmed_;
  VoxelMap static_, dynamic_;
  mutable std::size_t backfilled_ = 0;
};

}  // namespace dynobj::mapclean
