// SPDX-License-Identifier: BSD-3-Clause
// Analytic ray casting against the primitives scenes are made of: axis-aligned-in-yaw boxes,
// vertical cylinders and a bounded horizontal floor. World frame: +Z up.
#pragma once

#include <Eigen/Core>

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

/// Each returns true and fills `hit` when the ray meets the shape at 0 < t < hit_t_max.
bool intersect(const Box& b, const Ray& ray, double t_max, Hit& hit);
bool intersect(const Cylinder& c, const Ray& ray, double t_max, Hit& hit);
bool intersect(const Floor& f, const Ray& ray, double t_max, Hit& hit);

/// Bounding sphere (centre, radius) for broad-phase culling.
void boundingSphere(const Box& b, Eigen::Vector3d& c, double& r);
void boundingSphere(const Cylinder& c, Eigen::Vector3d& center, double& r);

}  // namespace dynobj::sim
