// SPDX-License-Identifier: BSD-3-Clause
// Before / after a filter, on a labelled sequence: how many points of a map (MRPT points-map text
// dump, world frame, e.g. icp-slam's) lie on the moving actors — within 0.2 m of a ground-truth
// dynamic point and more than 0.25 m above the floor (so the floor under the actors' feet does not
// count) — and one top-down picture of the two maps side by side, those points in red. Ground
// truth: the sequence's label file and TUM sensor poses (aligned by SequenceRunner).
#pragma once

#include <dynobj/mrptio/FrameSource.h>

#include <Eigen/Core>
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {

class ActorPoints {
 public:
  /// Every ground-truth dynamic point of `source`'s frames, in the world.
  static ActorPoints fromSequence(mrptio::FrameSource& source, const std::string& gt_labels,
                                  const std::string& gt_poses);
  void add(const Eigen::Vector3d& p);
  /// Within 0.2 m of a ground-truth dynamic point and higher than 0.25 m.
  bool onActor(const MapPoint& p) const;
  std::size_t size() const { return n_; }

 private:
  static long long key(const Eigen::Vector3d& p, int dx, int dy, int dz);
  std::unordered_map<long long, std::vector<Eigen::Vector3d>> cells_;  ///< 0.2 m voxel hash
  std::size_t n_ = 0;
};

/// "x y z ..." per line (MRPT's CPointsMap::save3D_to_text_file); other lines skipped. Throws
/// naming the file when it cannot be read.
std::vector<MapPoint> readPointsMapText(const std::string& path);

struct MapOnActors {
  std::size_t points = 0, on_actors = 0;
};
MapOnActors countOnActors(const std::vector<MapPoint>& map, const ActorPoints& actors);

/// Both maps from above on one scale, side by side (grey by height; points on actors red), each
/// under its caption.
cv::Mat renderSideBySide(const std::vector<MapPoint>& left, const std::string& left_caption,
                         const std::vector<MapPoint>& right, const std::string& right_caption,
                         const ActorPoints& actors, double resolution = 0.05);

}  // namespace dynobj::mapclean
