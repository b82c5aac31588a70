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

#include <utility>
#include <vector>

#include "dynobj/core/Clusterer.h"
#include "dynobj/core/FrameChain.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

struct MovementParams : public StageParams {
  int window = 5;                    ///< k: observations in the sliding window
  double min_displacement = 0.25;    ///< epsilon_d [m] over the window
  double min_straightness = 0.5;     ///< epsilon_o: f / f_a below this is drift
  double long_object_angle = 25.0 * M_PI / 180;  ///< epsilon_theta [rad; deg in INI]
  double long_object_elongation = 1.5;  ///< only clusters at least this elongated ...
  double long_object_length = 0.5;      ///< ... and this long [m] are tested for Eq. (23)
  double max_speed = 30.0;           ///< [m/s] faster is an association error, not motion

  void visit(ParamVisitor& v) override;
  void validate() const override;
};

/// One observation of a track: the frame index and the cluster centroid in that frame.
using WindowEntry = std::pair<long, Eigen::Vector3d>;
/// A track's sliding window, oldest first (a vector: k is small, and it is allocated once per track).
using Window = std::vector<WindowEntry>;

struct MovementDecision {
  bool enough_history = false;  ///< a full window of reliable frames
  double displacement = 0;      ///< f, Eq. (19) [m]
  double path = 0;              ///< f_a, Eq. (20) [m]
  double angle = M_PI / 2;      ///< theta, Eq. (23) [rad], pi/2 when not tested
  double speed = 0;             ///< f / window duration [m/s]
  bool candidate = false;       ///< f > epsilon_d
  bool drift = false;           ///< f / f_a < epsilon_o
  bool long_object = false;     ///< elongated and moving along itself
  bool static_surface = false;  ///< set by FreeSpaceCheck: its space was occupied already
  bool moving() const {
    return enough_history && candidate && !drift && !long_object && !static_surface;
  }
};

class MovementAnalyzer {
 public:
  explicit MovementAnalyzer(const MovementParams& p = {});

  /// `window`: the track's observations, oldest first (the last k are used); `cluster`: its
  /// current cluster (same frame as the last entry); `dt`: seconds between frames.
  MovementDecision analyse(const Window& window, const FrameChain& chain,
                           const Cluster& cluster, double dt) const;

  const MovementParams& params() const { return p_; }

 private:
  MovementParams p_;
};

}  // namespace dynobj::core
