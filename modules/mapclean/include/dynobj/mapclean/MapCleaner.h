// SPDX-License-Identifier: BSD-3-Clause
// The map-cleaning logic, without MRPT observations: which points of a scan are dynamic (the
// detector's mask, plus the back-fill), and the static / dynamic voxel maps.
//
// Back-fill: the detector is causal, so a moving object's first frames (before its movement
// window has enough history) are not flagged. A scan is mapped only backfill_window seconds after
// it was detected; by then the tracks confirmed dynamic since are known, and the points inside
// their boxes (grown by box_margin) in the scan are marked too, including frames before the track
// was confirmed. Memory: the window's records, not the recording's. It uses only the detector's
// output, never ground truth.
//
// Final voxels: a voxel into which no point has fallen for final_after seconds (nor into the
// other map's voxel at its key) is decided - the vote, the free-space check - and handed to the
// MapSink, static or dynamic, then forgotten: memory holds the voxels still in use (the place
// around the sensor), not the map of the whole recording. finish() decides the rest.
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
  /// [s] back-fill (see above): how long a scan waits for its tracks to be confirmed; 0 = off
  /// (each scan mapped as soon as its detection is final: causal)
  double backfill_window = 30.0;
  double box_margin = 0.15;  ///< [m] growth of a track's box sideways and upwards (back-fill)
  double min_range = 0.0;    ///< [m] points nearer than this (e.g. the robot itself) are not mapped
  /// Voxel vote (when a voxel is final): a static voxel moves to the dynamic map when it received
  /// at least this many times fewer static than dynamic points (0 = off; needs voxel_size > 0).
  double dynamic_vote = 1.0;
  /// Free-space check (MapVisibilityCheck.h) of the static map: every free_space_stride-th scan,
  /// as it is mapped, counts its views of the map so far; a final voxel not outvoted but seen
  /// through moves to the dynamic map (needs voxel_size > 0).
  bool free_space_check = true;
  /// Level every pose with the scan's floor (GroundLeveler.h): roll, pitch, height from the
  /// ground plane; for planar / drifting pose sources on a level floor. Off: assumes nothing.
  bool level_poses = false;
  int free_space_stride = 2;
  /// [s] a voxel no point has fallen into for this long is final (see above): decided and written
  /// out; 0 = every voxel stays in memory until the end
  double final_after = 20.0;
  /// The check's own parameters (INI keys free_space_margin, free_space_margin_rel,
  /// free_space_window, free_space_min_views, free_space_ratio, free_space_past; min_range is the
  /// one above).
  VisibilityParams visibility;

  /// `visibility` with this min_range.
  VisibilityParams freeSpace() const;

  void visit(core::ParamVisitor& v) override;
};

/// A tracked object of one frame, as the back-fill needs it (sensor frame box).
struct ObjectBox {
  int id = 0;
  bool dynamic = false;
  Eigen::Vector3f min{0, 0, 0}, max{0, 0, 0};
};

/// What is kept of a scan until it is mapped: small (no points).
struct FrameRecord {
  std::int64_t timestamp_ns = 0;
  Eigen::Isometry3d sensor_pose = Eigen::Isometry3d::Identity();  ///< in the world
  std::vector<std::uint32_t> dynamic_pixels;                      ///< detector output, ascending
  std::vector<ObjectBox> objects;
};

/// Where the final map points go, as they become final (MapCleaner).
class MapSink {
 public:
  virtual ~MapSink() = default;
  virtual void add(const MapPoint& p, bool dynamic) = 0;
};

/// A MapSink that keeps the points (small maps, tests): the static and the dynamic map.
struct MapCollector : public MapSink {
  std::vector<MapPoint> static_points, dynamic_points;
  void add(const MapPoint& p, bool dynamic) override {
    (dynamic ? dynamic_points : static_points).push_back(p);
  }
};

/// The voxel vote: moves to `dynamic` every voxel of `stat` that received `vote` times fewer
/// points than `dynamic` holds at its place (vote 0: none). Returns the voxels moved.
std::size_t voteVoxels(VoxelMap& stat, VoxelMap& dynamic, double vote);

class MapCleaner {
 public:
  /// `sink`: where the final points go (not owned; none: collected(), for small maps and tests).
  explicit MapCleaner(const MapCleanParams& p, MapSink* sink = nullptr);

  /// A scan's detection: keeps what mapping it needs and notes the tracks confirmed dynamic.
  FrameRecord record(const core::DetectionResult& r, const Eigen::Isometry3d& sensor_pose);

  /// Per-pixel dynamic mask of `frame`: the detector's pixels, plus (back-fill on) the pixels
  /// inside the boxes of the tracks confirmed dynamic so far.
  cv::Mat_<std::uint8_t> dynamicMask(const core::LidarFrame& frame, const FrameRecord& rec) const;

  /// Maps one scan: every valid pixel (placed with `sensor_pose`) into the static or dynamic map;
  /// then (every free_space_stride-th scan) its free-space views of the static map so far; then
  /// (every quarter of final_after) the voxels final by then go to the sink.
  void map(const core::LidarFrame& frame, const cv::Mat_<std::uint8_t>& dynamic_mask,
           const Eigen::Isometry3d& sensor_pose);

  /// A scan read only for its views (a chunk's scans before and after its own range,
  /// dynobj-mapclean --chunk-from/--chunk-to): its free-space views count as map() counts them, its
  /// points are not mapped.
  void look(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose);

  /// After the last scan: every voxel left is final (decided, to the sink).
  void finish();

  /// The voxels in use (not final yet).
  const VoxelMap& staticMap() const { return static_; }
  const VoxelMap& dynamicMap() const { return dynamic_; }
  /// Without a sink of one's own: the final points so far.
  const MapCollector& collected() const { return collected_; }
  /// Static voxels moved to the dynamic map so far: by the vote, by the free-space check.
  std::size_t voted() const { return voted_; }
  std::size_t seenThrough() const { return seen_through_; }
  /// Most voxels in use at once (both maps).
  std::size_t peakVoxels() const { return peak_voxels_; }
  const std::set<int>& confirmedTracks() const { return confirmed_; }
  std::size_t backfilledPixels() const { return backfilled_; }
  const MapCleanParams& params() const { return p_; }

 private:
  /// The voxels whose last point (in either map) came before `before` [ms stamp] are final: the
  /// vote (a static voxel with `dynamic_vote` times fewer points than the dynamic one at its key),
  /// then the free-space check decide a static voxel's map; each goes to the sink.
  void decide(std::uint32_t before);
  /// The stamp of a scan: milliseconds since the first mapped scan.
  std::uint32_t stampOf(std::int64_t timestamp_ns);

  MapCleanParams p_;
  MapCollector collected_;
  MapSink* sink_;
  std::set<int> confirmed_;
  VoxelMap static_, dynamic_;
  MapVisibilityCheck visibility_;
  std::size_t mapped_ = 0;  ///< scans mapped
  std::int64_t first_ns_ = 0;
  bool stamped_ = false;
  std::uint32_t decided_at_ = 0;  ///< stamp of the last decide()
  std::size_t voted_ = 0, seen_through_ = 0, peak_voxels_ = 0;
  mutable std::size_t backfilled_ = 0;
};

}  // namespace dynobj::mapclean
