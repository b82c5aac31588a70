// SPDX-License-Identifier: BSD-3-Clause
// Analytic ray casting against the primitives scenes are made of: axis-aligned-in-yaw boxes,
// vertical cylinders, a bounded horizontal floor, and the see-through clutter of outdoor scenes:
// porous volumes (foliage: tree crowns, bushes, hedges) and fences (bars and rails with gaps).
// World frame: +Z up.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>

namespace dynobj::sim {

struct Ray {
  Eigen::Vector3d origin;
  Eigen::Vector3d dir;  ///< unit length
};

/// The nearest intersection found so far.
struct Hit {
  double t = 0;            ///< distance along the ray [m]
  Eigen::Vector3d normal;  ///< unit surface normal, facing the ray origin
  Eigen::Vector2d uv;      ///< surface coordinates [m] for textures
  double gain = 1.0;       ///< reflectivity factor of this return (random for foliage, else 1)
};

/// Box rotated by `yaw` about +Z; `half` = half sizes along its own x, y, z.
struct Box {
  Eigen::Vector3d center{0, 0, 0};
  Eigen::Vector3d half{0.5, 0.5, 0.5};
  double yaw = 0;
};

/// Vertical cylinder: axis through (cx, cy), from z0 to z1.
struct Cylinder {
  Eigen::Vector2d center{0, 0};
  double radius = 0.25;
  double z0 = 0, z1 = 1.7;
};

/// Horizontal plane z = `z` limited to [xmin, xmax] x [ymin, ymax], seen from above.
struct Floor {
  double z = 0;
  double xmin = -50, xmax = 50, ymin = -50, ymax = 50;
};

/// Foliage: an ellipsoid (or a box: a hedge) of semi-axes / half sizes `half`, rotated by `yaw`
/// about +Z, that leaves and twigs fill sparsely. A ray crossing L metres of it returns with
/// probability 1 - exp(-density L) (≈ density L for short crossings), from an exponentially
/// distributed depth; which rays return is random per ray (see `intersect`).
struct Porous {
  Eigen::Vector3d center{0, 0, 1};
  Eigen::Vector3d half{1, 1, 1};
  double yaw = 0;
  bool ellipsoid = true;
  double density = 1.0;  ///< [1/m] hit probability per metre of traversal
};

/// Fence or railing: a vertical panel on the ground segment a -> b, from z0 to z1, made of
/// vertical bars `bar_width` wide every `bar_spacing` metres (one at each end; 0 = no bars),
/// horizontal rails `rail_width` thick at the heights `rails` (the first `rail_count`) and, if
/// `rail_spacing` > 0, every `rail_spacing` metres above z0 (wire mesh). A ray crossing the panel
/// on a bar or a rail hits it; through a gap it passes (the panel is thin: its depth is ignored).
struct Fence {
  Eigen::Vector2d a{0, 0}, b{1, 0};
  double z0 = 0, z1 = 1.2;
  double bar_width = 0.04, bar_spacing = 0.12;  ///< [m]
  double rail_width = 0.05, rail_spacing = 0;   ///< [m]
  std::array<double, 4> rails{};                ///< [m] rail centre heights
  int rail_count = 0;
};

/// Each returns true and fills `hit` when the ray meets the shape at 0 < t < hit_t_max.
bool intersect(const Box& b, const Ray& ray, double t_max, Hit& hit);
bool intersect(const Cylinder& c, const Ray& ray, double t_max, Hit& hit);
bool intersect(const Floor& f, const Ray& ray, double t_max, Hit& hit);
bool intersect(const Fence& f, const Ray& ray, double t_max, Hit& hit);
/// `key` seeds the ray's draws (hit depth, leaf orientation = normal, leaf reflectivity = gain):
/// the same key gives the same answer, another key an independent one. The simulator derives it
/// from the scenario seed, the sweep, the pixel and the part, so each sweep returns a different
/// random subset of the rays that cross the foliage.
bool intersect(const Porous& v, const Ray& ray, double t_max, std::uint64_t key, Hit& hit);

/// SplitMix64 step: a well-mixed 64-bit value from `state` (advanced), and a uniform in [0, 1).
std::uint64_t splitMix64(std::uint64_t& state);
double uniform01(std::uint64_t& state);

/// Bounding sphere (centre, radius) for broad-phase culling.
void boundingSphere(const Box& b, Eigen::Vector3d& c, double& r);
void boundingSphere(const Cylinder& c, Eigen::Vector3d& center, double& r);
void boundingSphere(const Porous& v, Eigen::Vector3d& center, double& r);
void boundingSphere(const Fence& f, Eigen::Vector3d& center, double& r);

}  // namespace dynobj::sim
