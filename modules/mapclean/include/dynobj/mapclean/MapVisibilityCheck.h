// SPDX-License-Identifier: BSD-3-Clause
// Visibility (free-space) check of a static voxel map, range-image based (as Removert, and the
// ray-casting of OctoMap / DUFOMap, do it): a voxel that some scans see *through* - its centre
// projects into a pixel whose measured range is clearly longer than the voxel's own range - was
// occupied only transiently (a person's trail the detector never confirmed), so it is moved to the
// dynamic map. Guards against removing static surfaces:
//  - beam width / grazing angles: the pixel must see beyond the voxel in a whole window of
//    (2 window + 1)^2 pixels (the nearest return of the window counts), so a floor or wall voxel
//    seen at a grazing angle, whose neighbouring beams hit the same surface nearer, is kept;
//  - range noise and pose error: "beyond" means by more than margin + margin_rel * range;
//  - a voxel that scans also see *at* its range (hits) is kept unless the see-through views
//    outnumber the hits by `ratio`, and at least `min_views` scans must see through it.
// Streams: the scans are added one at a time (e.g. a pass over the rawlog, or keyframes); memory is
// the candidate voxels (centre + two counters each), independent of the number of scans.
#pragma once

#include <dynobj/core/LidarFrame.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <vector>

#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::core {
class SphericalProjection;
}

namespace dynobj::mapclean {

/// Parameters of the map's visibility check (not the detector's core::FreeSpaceParams: this one
/// tests map voxels against whole scans).
struct VisibilityParams {
  double margin = 0.3;       ///< [m] a return must lie this much beyond the voxel ...
  double margin_rel = 0.05;  ///< ... plus this share of the voxel's range
  int window = 1;            ///< [px] half-size of the window whose nearest return must be beyond
  int min_views = 2;         ///< scans that must see through a voxel to remove it
  double ratio = 4.0;        ///< and see-through views >= ratio * hit views
  double min_range = 0.0;    ///< [m] voxels nearer to the sensor than this give no evidence
};

class MapVisibilityCheck {
 public:
  /// `voxels`: the candidates (key + centre), e.g. VoxelMap::voxels() of the static map.
  MapVisibilityCheck(const VisibilityParams& p, std::vector<VoxelCentre> voxels);
  ~MapVisibilityCheck();
  MapVisibilityCheck(const MapVisibilityCheck&) = delete;
  MapVisibilityCheck& operator=(const MapVisibilityCheck&) = delete;

  /// One scan (sensor frame) placed in the world with `sensor_pose`: counts, for every candidate
  /// in its field of view, a see-through view or a hit.
  void addScan(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose);

  /// Keys of the voxels seen through (the rule above), ascending.
  std::vector<std::uint64_t> seenThrough() const;
  std::size_t scans() const { return scans_; }
  /// Counters of candidate i (in the order given), for tests and diagnostics.
  std::uint16_t freeViews(std::size_t i) const { return free_[i]; }
  std::uint16_t hitViews(std::size_t i) const { return hit_[i]; }

 private:
  VisibilityParams p_;
  std::vector<VoxelCentre> voxels_;
  std::vector<std::uint16_t> free_, hit_;
  std::unique_ptr<core::SphericalProjection> projection_;
  cv::Mat_<float> nearest_;  ///< per pixel: nearest return of its window (+inf: none)
  std::size_t scans_ = 0;
};

}  // namespace dynobj::mapclean
