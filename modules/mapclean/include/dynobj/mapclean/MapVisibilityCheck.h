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
// the candidate voxels (centre + two counters each), independent of the number of scans. The
// candidates are either a fixed list (a finished map) or a growing VoxelMap, whose voxels carry
// their own counters (dynobj-mapclean's single pass: each scan counts against the map so far).
#pragma once

#include <dynobj/core/LidarFrame.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
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
  /// [s] a growing map (addScan with a VoxelMap): a voxel new in the map also counts the views
  /// of the scans added this long before it appeared (the place seen empty before someone came)
  double past = 30.0;
};

class MapVisibilityCheck {
 public:
  /// `voxels`: the candidates (key + centre), e.g. VoxelMap::voxels() of the static map.
  MapVisibilityCheck(const VisibilityParams& p, std::vector<VoxelCentre> voxels);
  ~MapVisibilityCheck();
  MapVisibilityCheck(const MapVisibilityCheck&) = delete;
  MapVisibilityCheck& operator=(const MapVisibilityCheck&) = delete;

  /// No fixed candidates: for addScan(frame, pose, map).
  explicit MapVisibilityCheck(const VisibilityParams& p);

  /// One scan (sensor frame) placed in the world with `sensor_pose`: counts, for every candidate
  /// in its field of view, a see-through view or a hit.
  void addScan(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose);
  /// The same for every voxel of `map`, into the voxels' own counters; the scan is remembered
  /// for countPast() (`past` seconds).
  void addScan(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose, VoxelMap& map);
  /// Voxels new in `map` (keys): the views of the remembered scans of the `past` seconds before
  /// `now_ns` (older ones are forgotten).
  void countPast(VoxelMap& map, const std::vector<std::uint64_t>& keys, std::int64_t now_ns);

  /// Keys of the candidates seen through (the rule above), ascending.
  std::vector<std::uint64_t> seenThrough() const;
  /// The rule: enough scans saw through it, and they outnumber its hits by `ratio`.
  bool isSeenThrough(const VoxelMap::Views& v) const {
    return v.free >= p_.min_views && v.free >= p_.ratio * v.hit;
  }
  std::size_t scans() const { return scans_; }
  /// Counters of candidate i (in the order given), for tests and diagnostics.
  std::uint16_t freeViews(std::size_t i) const { return views_[i].free; }
  std::uint16_t hitViews(std::size_t i) const { return views_[i].hit; }

 private:
  /// What counting needs of a scan; a remembered one keeps its images in half floats (CV_16F:
  /// 1.6 cm steps at 20-32 m, far below the margin; half the memory).
  struct ScanView {
    std::int64_t timestamp_ns = 0;
    /// Per pixel (CV_32FC2 or CV_16FC2, one read for both): [0] the range [m], 0 = no return;
    /// [1] the nearest return of its window, +inf: none.
    cv::Mat images;
    Eigen::Isometry3f to_sensor = Eigen::Isometry3f::Identity();
    float near = 0, far = 0;
  };
  /// The scan as a ScanView (and the projection for its sensor).
  ScanView prepare(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose);
  /// Counts one world point's view in `scan` (T: the images' element type).
  template <class T>
  void count(const ScanView& scan, float x, float y, float z, VoxelMap::Views& views) const;

  VisibilityParams p_;
  std::vector<VoxelCentre> voxels_;
  std::vector<VoxelMap::Views> views_;
  std::unique_ptr<core::SphericalProjection> projection_;
  std::deque<ScanView> past_;  ///< addScan(.., map)'s scans of the last `past` seconds
  std::size_t scans_ = 0;
};

}  // namespace dynobj::mapclean
