// SPDX-License-Identifier: BSD-3-Clause
// Paper III-B-2, Eq. (6)-(7): Euclidean clustering of the foreground points with separate
// horizontal (d_xy) and vertical (d_z) thresholds: two points are neighbours when
// d_xy <= horizontal_distance and d_z <= vertical_distance; clusters are the connected components
// (single linkage, the usual reading of Eq. 7). Neighbours are found in a uniform grid of
// epsilon-sized cells, O(n) (a unit test checks the links against brute force).
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

struct ClusteringParams : public StageParams {
  double horizontal_distance = 0.35;  ///< epsilon_xy [m]
  double vertical_distance = 0.6;     ///< epsilon_z [m]
  int min_points = 3;                 ///< smaller clusters are dropped ...
  /// ... unless they have at least this many points: such a weak cluster only seeds a track that
  /// is already dynamic and found no cluster of min_points (a mover whose features dip below
  /// min_points for a sweep; 0 or >= min_points = off). Beyond the paper, docs/algorithm.md §5
  int weak_min_points = 2;
  int max_points = 100000;  ///< larger clusters are dropped (a safety bound in pixels)
  double max_area = 20.0;   ///< [m^2] with voxel > 0: clusters whose features fill
                            ///< more voxels than this area are dropped (facades, shelves); a car
                            ///< seen from 2 m fills ~10 m^2 (0 = no limit)
  double voxel = 0.17;      ///< [m] one point per voxel of this size (0 = all)

  void visit(ParamVisitor& v) override;
  void validate() const override;
};

struct Cluster {
  std::vector<int> pixels;                     ///< pixel indices (row * W + col) of its points
  Eigen::Vector3d centroid{0, 0, 0};           ///< sensor frame [m]
  Eigen::Vector3d min{0, 0, 0}, max{0, 0, 0};  ///< axis-aligned bounds
  Eigen::Vector2d main_direction{1, 0};        ///< Eq. (22): horizontal PCA main axis (unit)
  double elongation = 1.0;  ///< sqrt(lambda1 / lambda2) of the horizontal covariance
  double length = 0.0;      ///< extent along the main axis [m]
  Eigen::Vector3d end_a{0, 0, 0},
      end_b{0, 0, 0};  ///< the two ends along the main axis (z = centroid's)
};

/// Mean of the points at `pixels` (the origin when there are none).
Eigen::Vector3d centroidOf(const LidarFrame& frame, const std::vector<int>& pixels);

/// Fills centroid, bounds and PCA fields of `c` from its pixels.
void computeClusterShape(const LidarFrame& frame, Cluster& c);

class Clusterer {
 public:
  explicit Clusterer(const ClusteringParams& p = {});
  /// Clusters the valid pixels set in `features` (255): `out` the clusters of min_points or
  /// more, `weak` (when given) those of weak_min_points up to min_points - 1, with their pixels
  /// and centroid only (computeClusterShape() gives the rest).
  /// `dropped` (when given): the feature pixels of the clusters dropped for their size
  /// (max_area, max_points), all in one list.
  void cluster(const LidarFrame& frame, const cv::Mat_<std::uint8_t>& features,
               std::vector<Cluster>& out, std::vector<Cluster>* weak = nullptr,
               std::vector<int>* dropped = nullptr);

 private:
  void clusterPoints(const LidarFrame& frame, std::vector<int>& label);
  void linkGrid(std::vector<int>& parent);  ///< union-find over pts_, from a cell grid

  ClusteringParams p_;
  std::vector<int> pixels_;
  std::vector<int> count_, slot_;
  std::vector<int> voxels_;  ///< per component label: voxels (representatives) it spans
  std::vector<int> label_, parent_, rep_of_, first_feature_;  ///< per-frame scratch, kept
  std::vector<std::uint64_t> slot_key_;  ///< voxel hash table: key of each slot ...
  std::vector<int> slot_rep_;            ///< ... and its representative (index in pts_)
  std::vector<std::pair<std::uint64_t, int>> cells_;      ///< grid cell key, index in pts_
  std::vector<std::pair<std::uint64_t, int>> cells_tmp_;  ///< sorting scratch
  std::vector<int> counts_;                               ///< sorting scratch
  std::vector<Eigen::Vector3f> spts_;                     ///< pts_ in cell order
  std::vector<int> sparent_;                              ///< union-find over spts_
  std::vector<Eigen::Vector3f> pts_;  ///< (x, y, z * horizontal/vertical): isotropic for the tree
};

}  // namespace dynobj::core
