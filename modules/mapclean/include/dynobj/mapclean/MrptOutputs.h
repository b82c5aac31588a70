// SPDX-License-Identifier: BSD-3-Clause
// MRPT outputs of map cleaning:
//  - a cleaned .simplemap: keyframe scans (every `keyframe_distance` m or `keyframe_angle` rad,
//    0 = every scan) as CObservation3DRangeScan with the dynamic points dropped and tagged
//    (docs/formats.md §4), at their robot poses, so observations2map / icp-slam-style tools rebuild
//    a clean map. Only keyframes are held in memory;
//  - point maps as CPointsMapXYZI: serialized (".pointsmap", gzip, read back with
//    archiveFrom(CFileGZInputStream) >> map) and as "x y z intensity" text.
#pragma once

#include <mrpt/maps/CSimpleMap.h>

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "dynobj/mapclean/ScanSource.h"
#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {

class CleanedSimplemapWriter {
 public:
  CleanedSimplemapWriter(std::string path, double keyframe_distance, double keyframe_angle);

  /// Adds `scan` if it is a keyframe: its observation (a copy; other LiDAR types become an
  /// organized CObservation3DRangeScan of its frame) with `dynamic_mask`'s pixels dropped.
  void add(const Scan& scan, const cv::Mat_<std::uint8_t>& dynamic_mask,
           const Eigen::Isometry3d& sensor_pose);
  std::size_t keyframes() const { return map_.size(); }
  /// Saves to "<path>.partial" and renames. Throws naming the file on failure.
  void close();

 private:
  std::string path_;
  double dist_, angle_;
  mrpt::maps::CSimpleMap map_;
  bool have_last_ = false;
  Eigen::Isometry3d last_ = Eigen::Isometry3d::Identity();
};

/// Concatenates the keyframes of simplemaps, each moved into the world by its transform (applied
/// to the keyframes' poses, on the left), into `path` atomically. Returns the keyframes. Throws
/// naming a file that cannot be read or written.
std::size_t mergeSimplemaps(const std::vector<std::pair<std::string, Eigen::Isometry3d>>& parts,
                            const std::string& path);

/// Writes `file` (serialized CPointsMapXYZI, gzip), atomically.
void writePointsMapFile(const std::string& file, const std::vector<MapPoint>& points);
/// Writes `file` ("x y z intensity" lines, CPointsMapXYZI::saveXYZI_to_text_file), atomically.
void writePointsMapText(const std::string& file, const std::vector<MapPoint>& points);

}  // namespace dynobj::mapclean
