// SPDX-License-Identifier: BSD-3-Clause
// Before / after a filter: two maps of one sequence (MRPT points-map text dumps, world frame, e.g.
// icp-slam's on the raw and on the filtered rawlog), compared two ways, and one top-down picture
// of the two side by side with the points counted in red:
//  - with ground truth (the sequence's label file and TUM sensor poses): the points on the moving
//    actors - within 0.2 m of a ground-truth dynamic point and more than 0.25 m above the floor
//    (so the floor under the actors' feet does not count);
//  - label-free (any recording): the points that the sweeps see through (MapVisibilityCheck's
//    rule), each map checked with the poses that built it - the trails of moving objects are
//    what later sweeps see through.
#pragma once

#include <dynobj/mrptio/FrameSource.h>

#include <Eigen/Core>
#include <cstddef>
#include <opencv2/core.hpp>
#include <string>
#include <unordered_map>
#include <vector>

#include "dynobj/mapclean/MapVisibilityCheck.h"
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
/// Per map point: on a moving actor (ActorPoints::onActor).
std::vector<bool> onActors(const std::vector<MapPoint>& map, const ActorPoints& actors);

/// Label-free, per map point: the sweeps of `source` see through it (MapVisibilityCheck's rule
/// with `p`, every map point a candidate), the sweeps placed by `pose_spec` (PoseSource's specs:
/// the TUM file or the simplemap of the run that built the map, "odometry", "ego"); the detector
/// runs for the ego-motion when the spec needs it. `poses_used`, when given, receives the pose
/// source's description. Throws naming the pose file / the scan without a pose.
std::vector<bool> seenThrough(const std::vector<MapPoint>& map, mrptio::FrameSource& source,
                              const std::string& pose_spec, const VisibilityParams& p = {},
                              std::string* poses_used = nullptr);

/// Both maps from above on one scale, side by side (grey by height; the marked points red, the
/// legend says what they are), each under its caption, with a scale bar.
cv::Mat renderSideBySide(const std::vector<MapPoint>& left, const std::vector<bool>& left_marked,
                         const std::string& left_caption, const std::vector<MapPoint>& right,
                         const std::vector<bool>& right_marked, const std::string& right_caption,
                         const std::string& marked_means, double resolution = 0.05);

}  // namespace dynobj::mapclean
