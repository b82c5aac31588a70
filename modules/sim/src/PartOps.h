// SPDX-License-Identifier: BSD-3-Clause
// Internal: operations on the parts of a scene, whatever their shape (LidarSimulator.cpp).
#pragma once

#include <cstdint>

#include "dynobj/sim/PoseTrack.h"
#include "dynobj/sim/Scenario.h"

namespace dynobj::sim::detail {

/// An actor's part (box or cylinder, in the actor frame) placed at the actor's pose.
Part placed(const Part& p, const Pose2& pose);
/// Nearest hit of `ray` on the part before t_max. `pixel_key` (sweep and pixel) and `uid` (the
/// part's index in the posed world) key the random draws of foliage; solid hits have gain 1.
bool intersectPart(const Part& p, const Ray& ray, double t_max, std::uint64_t pixel_key,
                   std::uint32_t uid, Hit& hit);
/// Foliage swaying in the wind at time t [s]; other parts are returned unchanged.
Part swayed(const Part& p, double t, std::uint32_t uid);
/// A walker's limb (Part::swing != 0) at time t [s] for an actor walking at `speed` [m/s]: shifted
/// along the actor's x on a stride cycle of 0.9 Hz, by the full swing at 1.4 m/s and above, with
/// a phase of its own per actor. Other parts are returned unchanged.
Part swung(const Part& p, double t, double speed, int actor);
/// Bounding sphere of any part.
void boundingSphere(const Part& p, Eigen::Vector3d& center, double& r);

}  // namespace dynobj::sim::detail
