// SPDX-License-Identifier: BSD-3-Clause
// The tracks: one per associated cluster, each with its sliding window of observations. Beyond
// the paper (its stated limits, both switchable): a constant-velocity Kalman filter predicts a
// track through short occlusions so it keeps its identity and window, and hysteresis keeps a
// moving object's state from flickering frame to frame.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "dynobj/core/ClusterAssociator.h"
#include "dynobj/core/Clusterer.h"
#include "dynobj/core/MovementAnalyzer.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

struct TrackingParams : public StageParams {
  bool prediction = true;      ///< Kalman prediction (false: the paper's Eq. 8 only, no coasting)
  int max_missed = 5;          ///< frames a track coasts unseen before it is dropped
  double process_noise = 2.0;  ///< [m/s^2] white acceleration of the constant-velocity model
  double measurement_noise = 0.1;  ///< [m] centroid noise
  bool hysteresis = true;    ///< confirm / release counters (false: state = this frame's test)
  int confirm_frames = 2;    ///< consecutive moving decisions to become dynamic
  int release_frames = 4;    ///< consecutive static decisions to become static again
  int settled_frames = 10;   ///< a track judged static this many times in a row is settled
  bool stop_at_rest = true;  ///< a mover released by a clear stop ([movement] stop_window) is at
                             ///< rest at once, not only once settled (a walker who pauses beside
                             ///< a passer; false = only once settled)

  void visit(ParamVisitor& v) override;
};

struct Track {
  int id = 0;
  int age = 0;       ///< frames since the track was born
  int missed = 0;    ///< consecutive frames without a cluster
  int cluster = -1;  ///< index of this frame's cluster, -1 when unseen
  Window window;     ///< observations (frame, centroid in that frame), at most k + 1
  Eigen::Vector4d state{0, 0, 0, 0};  ///< x, y, vx, vy in the current frame
  Eigen::Matrix4d cov = Eigen::Matrix4d::Identity();
  double z = 0;       ///< last observed centroid height
  double radius = 0;  ///< [m] half the horizontal diagonal of its last cluster's box
  bool dynamic = false;
  int positives = 0, negatives = 0;
  bool settled = false;  ///< judged static settled_frames times in a row since it last moved
  bool halted = false;   ///< released by a clear stop (stop_at_rest) and not moving since
  MovementDecision decision;
  /// At rest (atRest): the points of its last cluster, in the sensor frame of sweep shape_frame
  /// (SettledSplit.h); empty otherwise.
  std::vector<Eigen::Vector3f> shape;
  long shape_frame = -1;

  /// Settled, or a mover that clearly stopped: its last points are its own (SettledSplit.h).
  bool atRest() const { return (settled || halted) && !dynamic; }
  Eigen::Vector3d position() const { return {state(0), state(1), z}; }
  Eigen::Vector2d velocity() const { return state.tail<2>(); }
};

class TrackManager {
 public:
  TrackManager(const TrackingParams& p, int window);

  /// Moves every track into the current frame: T_{prev<-cur} = `motion` (Eq. 8), then the
  /// constant-velocity prediction over `dt` seconds when enabled.
  void predict(const Eigen::Isometry3d& motion, double dt);
  /// Predicted centroids, in track order (the "R c + t" of Eq. 8).
  std::vector<Eigen::Vector3d> predicted() const;
  /// Each track's association gate (ClusterAssociator::gate): wider for a track seen once (no
  /// velocity yet) over the `dt` seconds per sweep it went unseen.
  std::vector<double> gates(const ClusterAssociator& a, double dt) const;
  /// Each track: moving at the last sweep and seen there (associated first).
  std::vector<char> movers() const;
  /// Applies the association: `cluster_to_track[m]` = track index or -1 (new track).
  void update(long frame, const std::vector<Cluster>& clusters,
              const std::vector<int>& cluster_to_track);
  /// Sets a seen track's moving state from this frame's decision (with hysteresis).
  void decide(Track& t, const MovementDecision& d);
  void reset();

  std::vector<Track>& tracks() { return tracks_; }
  const std::vector<Track>& tracks() const { return tracks_; }

 private:
  TrackingParams p_;
  std::size_t window_;
  std::vector<Track> tracks_;
  int next_id_ = 0;
};

}  // namespace dynobj::core
