// SPDX-License-Identifier: BSD-3-Clause
// Paper III-C, Eq. (14)-(23): does a tracked cluster move?
//  - movement analysis (Eq. 14-19): the centroids of the last k observations are expressed in the
//    window's first frame through the accumulated frame-to-frame transforms; f = distance between
//    the last and the first. A moving candidate has f > epsilon_d (the paper's text says "less";
//    that inverts the test, see docs/algorithm.md).
//  - drift (Eq. 20): path length f_a; the ratio f / f_a below epsilon_o is jitter, not travel.
//  - long objects (Eq. 21-23): angle between the moving direction and the cluster's PCA main
//    direction; an elongated cluster "sliding" along its own axis (a wall seen from a moving
//    robot) is rejected when the angle is below epsilon_theta.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <utility>
#include <vector>

#include "dynobj/core/Clusterer.h"
#include "dynobj/core/FrameChain.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

struct MovementParams : public StageParams {
  int window = 5;       ///< k: observations in the sliding window
  int min_window = 3;   ///< fewer observations than k, but at least this many, already give a
                        ///< "moving" verdict when they show epsilon_d of straight travel (a fast
                        ///< object is flagged sooner; beyond the paper; real data_2 online F1
                        ///< +0.013). >= window: off
  int stop_window = 3;  ///< beyond the paper: a track whose last stop_window observations ...
  double stop_speed = 0.3;  ///< ... moved slower than this [m/s] has stopped: not moving, and a
                            ///< dynamic track is released at once (no hysteresis); 0 = off
  /// epsilon_d [m] over the window: 0.2 m in the k - 1 = 4 steps of 0.1 s is 0.5 m/s, hindsight's
  /// min_speed (with 3-D steps a walker's height jitter needs 0.25 m)
  double min_displacement = 0.2;
  double min_straightness = 0.5;  ///< epsilon_o: f / f_a below this is drift
  /// Beyond the paper: f and f_a over the centroids' horizontal steps (the x-y plane of the
  /// window's first sensor frame). A cluster's height jitters with the features it holds (a far
  /// walker's 3..10 features sit on its head one sweep and its legs the next), which adds to f_a
  /// and reads as drift; things move along the ground. false = 3-D steps, the paper.
  bool planar = true;
  double long_object_angle = 25.0 * M_PI / 180;  ///< epsilon_theta [rad; deg in INI]
  /// [m] beyond the paper: an upright cluster (at least upright_height tall) no longer than this,
  /// a walker or a rider on a two-wheeler, is not rejected by Eq. (23): its few points give no
  /// ends to tell it from a wall sliding by (rigid_tolerance), so the free-space check alone
  /// judges it (riders in groups on simulated `traffic`: cyclist recall 0.22 -> 0.37 on OS1-64;
  /// docs/algorithm.md §7). 0 = Eq. (23) for every cluster, the paper
  double upright_length = 2.0;
  double upright_height = 1.0;  ///< [m] ... (a low cluster that short is a parked car's flank)
  /// ... and no more elongated than this (sqrt(lambda1 / lambda2): about length / width; a slice
  /// of a fence or a wall is flatter, a rider 5-8)
  double upright_max_elongation = 10.0;
  double rigid_tolerance = 0.3;  ///< a long object whose two ends both moved like its centroid
                                 ///< (within this fraction of f) is a rigid mover (a car), not a
                                 ///< wall sliding into view: exempt from Eq. (23); 0 = never
  /// [m] ... or, for a cluster at least this long in both, whose two ends moved alike (within
  /// rigid_tolerance of their mean) and farther than its centroid: a car passing the sensor,
  /// whose densest points stay abreast of the sensor while its ends move with it (a short
  /// cluster's ends are noise). Beyond the paper; 0 = off
  /// (docs/algorithm.md §7).
  double rigid_ends_length = 2.0;
  /// Eq. (23) rejects a long object only when its displacement f is at most this many times the
  /// sensor's own travel over the window: a static wall's visible part slides only because the
  /// viewpoint moves, by about as far (more where a near occluder frames it), while a car driving
  /// along its axis past a stopped or slower sensor moves farther. 0 = always (the paper; 1.5
  /// flagged facades framed by trees on `plaza`, 3 does not; docs/algorithm.md §7).
  double long_object_ego_ratio = 3.0;
  double max_speed = 30.0;  ///< [m/s] faster is an association error, not motion

  void visit(ParamVisitor& v) override;
  void validate() const override;
};

/// One observation of a track, in the sensor frame of its own frame: the cluster centroid and the
/// two ends of the cluster along its horizontal main axis (both = centroid when unknown).
struct WindowEntry {
  long frame = 0;
  Eigen::Vector3d centroid{0, 0, 0};
  Eigen::Vector3d end_a{0, 0, 0}, end_b{0, 0, 0};
  WindowEntry(long f, const Eigen::Vector3d& c) : frame(f), centroid(c), end_a(c), end_b(c) {}
  WindowEntry(long f, const Eigen::Vector3d& c, const Eigen::Vector3d& a, const Eigen::Vector3d& b)
      : frame(f), centroid(c), end_a(a), end_b(b) {}
};
/// A track's sliding window, oldest first (a vector: k is small, and it is allocated once per
/// track).
using Window = std::vector<WindowEntry>;

struct MovementDecision {
  bool enough_history = false;  ///< at least min_window observations over reliable frames
  bool early = false;           ///< judged on fewer than k observations: only "moving" counts
  bool stopped = false;         ///< its last stop_window observations moved slower than stop_speed
  double displacement = 0;      ///< f, Eq. (19) [m]
  double path = 0;              ///< f_a, Eq. (20) [m]
  double angle = M_PI / 2;      ///< theta, Eq. (23) [rad], pi/2 when not tested
  double speed = 0;             ///< f / window duration [m/s]
  Eigen::Vector3d velocity{0, 0, 0};  ///< f's vector / window duration, current frame [m/s]
  bool candidate = false;             ///< f > epsilon_d
  bool drift = false;                 ///< f / f_a < epsilon_o
  bool long_object = false;           ///< elongated and moving along itself
  bool rigid = false;                 ///< elongated, and both its ends moved with the centroid
  bool slides = false;          ///< rigid, moving along its own axis where the viewpoint moved as a
                                ///< wall's visible part does (FreeSpaceParams::slide_free_ratio)
  bool static_surface = false;  ///< set by FreeSpaceCheck: its space was occupied already
  /// set by FreeSpaceCheck: static_surface, and hardly any of its space was free (a free share
  /// below release_free_ratio): like a stop, it releases a dynamic track at once
  bool refuted = false;
  bool porous = false;  ///< set by FreeSpaceCheck: seen through (foliage)
  bool moving() const {
    return enough_history && candidate && !drift && !long_object && !static_surface && !porous &&
           !stopped;
  }
};

class MovementAnalyzer {
 public:
  explicit MovementAnalyzer(const MovementParams& p = {});

  /// `window`: the track's observations, oldest first (the last k are used); `cluster`: its
  /// current cluster (same frame as the last entry); `dt`: seconds between frames; `at_rest`: the
  /// track is at rest (Track::atRest), and its ends alone do not make it rigid (rigid_ends_length:
  /// a walker who merges with a resting object shifts its ends).
  MovementDecision analyse(const Window& window, const FrameChain& chain, const Cluster& cluster,
                           double dt, bool at_rest = false) const;

  const MovementParams& params() const { return p_; }

 private:
  /// Both ends of `b` (the last entry) moved from those of `a` (the first) by the centroid's
  /// displacement along v, or (`by_ends`, rigid_ends_length) both by their mean, farther than the
  /// centroid; T_ab maps b's frame into a's.
  bool rigidMotion(const WindowEntry& a, const WindowEntry& b, const Eigen::Isometry3d& T_ab,
                   const Eigen::Vector3d& v, double displacement, bool by_ends) const;

  MovementParams p_;
};

}  // namespace dynobj::core
