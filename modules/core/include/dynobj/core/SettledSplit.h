// SPDX-License-Identifier: BSD-3-Clause
// Beyond the paper (docs/algorithm.md §5): one cluster may hold a mover and an object settled at
// rest — a walker passing one who stands, or a tree. Associated whole to either track, it flags the
// one at rest (with the mover's track) or hides the mover (with the other's). It is split between
// the two tracks by the resting object's own last points.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dynobj/core/Clusterer.h"
#include "dynobj/core/FrameChain.h"
#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/TrackManager.h"

namespace dynobj::core {

struct SettledSplitParams {
  double radius = 0.2;          ///< [m] a point this near one of the resting object's is its ...
  double z_scale = 0.35 / 0.6;  ///< ... heights scaled as the clustering's (eps_xy / eps_z)
  double margin = 0.35;         ///< [m] the other track's prediction lies within the box + this
  int min_points = 4;           ///< a part smaller than this is no part
  double min_share = 0.25;      ///< both parts hold at least this share of the cluster's points
  double match_radius = 0.1;    ///< [m] ... but the mover's part may be smaller when its centroid
                                ///< lies this near the mover's prediction
  bool rest_majority = true;    ///< no split, the mover's cluster mostly the resting object's:
                                ///< the resting track takes it whole
  bool hold_back = true;        ///< no split, the mover keeps its cluster: the resting object's
                                ///< fair part in it is held back (`held`)
};

/// For each track at rest (Track::atRest) or dynamic that `cluster_to_track` left without a
/// cluster, and a cluster associated with a track of the other kind that reaches its `predicted`
/// centroid (box + `margin`): the cluster's points within `radius` of the resting track's shape
/// (moved into sweep `frame_index` by `chain`) are the resting object's, the others the mover's.
/// - the resting object's part is too small (< min_points): nothing changes;
/// - the mover's is: the whole cluster goes to the resting track (the mover coasts);
/// - else, only when each part holds `min_share` of the points (the mover's part may hold fewer
///   when its centroid lies within `match_radius` of the mover's prediction) and the mover's part
///   lies within `radius` of the mover's prediction, the cluster is split: each track takes its
///   part;
/// - else, when the resting track found no cluster and its part holds half of the points or
///   more (`rest_majority`), the whole cluster goes to the resting track (the mover coasts).
/// - else, when the cluster stays with the mover's track although the resting object holds a
///   fair part of it (`min_share`: the mover's part only lay off its prediction), that part is
///   appended to `held` (when given and `hold_back`): the mover's track keeps the whole cluster,
///   but those points are the resting object's, neither seeds nor grown into.
/// New parts are appended to `clusters` and `cluster_to_track`. Returns the ids of the resting
/// tracks given a part (they keep their shape: rememberShapes' `keep`).
std::vector<int> splitSettled(const SettledSplitParams& p, const LidarFrame& frame,
                              long frame_index, const FrameChain& chain,
                              const std::vector<Track>& tracks,
                              const std::vector<Eigen::Vector3d>& predicted,
                              std::vector<Cluster>& clusters, std::vector<int>& cluster_to_track,
                              std::vector<int>* held = nullptr);

/// Stores on each seen track at rest the points of its cluster in sweep `frame_index` (its
/// shape for splitSettled), except on the tracks whose id is in `keep`; clears the shape of every
/// other track that was seen.
void rememberShapes(const LidarFrame& frame, long frame_index, const std::vector<Cluster>& clusters,
                    const std::vector<int>& keep, std::vector<Track>& tracks);

}  // namespace dynobj::core
