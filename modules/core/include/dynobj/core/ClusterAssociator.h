// SPDX-License-Identifier: BSD-3-Clause
// Paper III-B-3, Eq. (8)-(13): Global Nearest Neighbour association of the current clusters with
// the tracks, by the Hungarian method on a cost matrix extended with dummy targets.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dynobj/core/Params.h"

namespace dynobj::core {

struct AssociationParams : public StageParams {
  double gate_distance = 1.0;  ///< d_max [m]: farther pairs cost "infinity" (Eq. 9)
  /// [m/s] beyond the paper: a track seen once has no velocity yet, so its gate is
  /// d_max + this x the seconds since it was seen (a car at 11 m/s moves 1.1 m per 10 Hz sweep:
  /// with d_max alone its every sweep starts a new track). 0 = the paper's d_max for every track
  double new_track_speed = 15.0;
  /// [m] ... for a cluster at least this long (along its main axis) when seen: only vehicles are
  /// that fast, and a walker's first cluster linked to clutter 2 m away starts its window with
  /// a jump (its detection then waits until the jump leaves the window)
  double new_track_length = 1.0;
  /// [m] beyond the paper (docs/algorithm.md §5, SettledSplit.h): a cluster that holds both a
  /// mover and an object settled at rest (a walker passing one who stands, or a tree) is split
  /// between their tracks: its points within this horizontal distance of the resting object's
  /// last points are the resting object's. 0 = the paper: the merged cluster is one observation
  double split_radius = 0.2;
  /// ... only when each part holds at least this share of the merged cluster's points (a sliver
  /// is the edge of one object: a car's end over the place of a small thing it hid)
  double split_min_share = 0.25;
  /// [m] ... except that a mover's part under that share is still the mover's when its centroid
  /// lies this near the mover's prediction (a walker beside a wall or a parked car, which holds
  /// far more points); 0 = off
  double split_match_radius = 0.1;
  /// when no split is made and the mover's track took the cluster, the resting object's track
  /// takes it whole if its part holds at least half of the points (the mover coasts; false = the
  /// mover keeps it, and with it the resting object)
  bool split_rest_majority = true;
  /// when no split is made and the mover's track keeps the cluster, the resting object's part in
  /// it (a share of at least split_min_share) is held back: neither seeds nor grown into
  /// (false = flagged with the mover)
  bool split_hold_back = true;
  /// beyond the paper: the tracks of objects moving at the last sweep are associated first, with
  /// the clusters nearest to them of all predictions and within half their gate; then every other
  /// track with the clusters left. A big
  /// mover often shows as one large cluster and small ones beside it, each with a track: with one
  /// global assignment a young track next to the mover's cluster can take it, and the mover,
  /// handed a small one, is lost and confirmed again ~0.5 s later (real HDL-64 data_2: online F1
  /// +0.020). false = the paper's one assignment
  bool movers_first = true;
  /// beyond the paper: a dynamic track that found no cluster where features were dropped with a
  /// cluster too large to keep (ClusteringParams::max_area: a walker touching a hedge, a fence or
  /// a row of parked cars merges with it) takes those of them within its own extent + 0.2 m of
  /// its prediction whose space the free-space lookback frame saw free, as its cluster (real
  /// data_2: a pedestrian walking along a hedge, lost for 10 sweeps; online F1 +0.008)
  bool carve_dropped = true;

  void visit(ParamVisitor& v) override;
};

class ClusterAssociator {
 public:
  explicit ClusterAssociator(const AssociationParams& p = {});

  /// The gate of a track [m]: d_max, widened by new_track_speed x `unknown_velocity_seconds`
  /// (the seconds since a track without a velocity was seen; 0 for a track with one) when the
  /// cluster it was seen with is at least new_track_length long (`length` [m]).
  double gate(double unknown_velocity_seconds, double length) const;

  /// The (M+N) x (N+M) matrix of Eq. (10): rows = M current clusters then N dummies, columns =
  /// N predicted tracks then M dummies. Real pairs cost their distance (Eq. 8) or `forbidden`
  /// beyond the track's gate (Eq. 9; `gates[n]`, d_max for every track when empty); a real row
  /// or column paired with a dummy costs 2 d_max; dummy-dummy 0. (So a pair farther than 4 d_max
  /// never beats leaving both unpaired: a wide gate reaches at most that far.)
  Eigen::MatrixXd costMatrix(const std::vector<Eigen::Vector3d>& current,
                             const std::vector<Eigen::Vector3d>& predicted,
                             const std::vector<double>& gates = {}) const;

  /// For each current cluster, the index of its track in `predicted`, or -1 (a new object).
  /// `gates`: one per track (see gate()), or empty for d_max everywhere.
  std::vector<int> associate(const std::vector<Eigen::Vector3d>& current,
                             const std::vector<Eigen::Vector3d>& predicted,
                             const std::vector<double>& gates = {}) const;

  /// associate() in two rounds when movers_first: first the tracks flagged in `first` (the
  /// movers seen at the last sweep) with the clusters whose nearest prediction is a mover's, within
  /// half its gate; then the tracks still unpaired with the clusters the first round left; one
  /// round over all tracks otherwise.
  std::vector<int> associateMoversFirst(const std::vector<Eigen::Vector3d>& current,
                                        const std::vector<Eigen::Vector3d>& predicted,
                                        const std::vector<double>& gates,
                                        const std::vector<char>& first) const;

  double forbidden() const { return 1e6 * p_.gate_distance; }

 private:
  AssociationParams p_;
};

}  // namespace dynobj::core
