// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/Shapes.h"

#include <cmath>
#include <limits>

namespace dynobj::sim {

bool intersect(const Box& b, const Ray& ray, double t_max, Hit& hit) {
  // Into the box frame (rotation about Z by -yaw).
  const double c = std::cos(b.yaw), s = std::sin(b.yaw);
  const Eigen::Vector3d d0 = ray.origin - b.center;
  const Eigen::Vector3d o(c * d0.x() + s * d0.y(), -s * d0.x() + c * d0.y(), d0.z());
  const Eigen::Vector3d d(c * ray.dir.x() + s * ray.dir.y(), -s * ray.dir.x() + c * ray.dir.y(),
                          ray.dir.z());
  double t0 = -std::numeric_limits<double>::infinity(),
         t1 = std::numeric_limits<double>::infinity();
  int axis0 = -1;
  double sign0 = 0;
  for (int k = 0; k < 3; k++) {  // slab test, remembering the entry face
    if (std::abs(d[k]) < 1e-12) {
      if (o[k] < -b.half[k] || o[k] > b.half[k]) return false;
      continue;
    }
    double ta = (-b.half[k] - o[k]) / d[k], tb = (b.half[k] - o[k]) / d[k];
    double sgn = -1;  // entering through the -half face
    if (ta > tb) {
      std::swap(ta, tb);
      sgn = 1;
    }
    if (ta > t0) {
      t0 = ta;
      axis0 = k;
      sign0 = sgn;
    }
    t1 = std::min(t1, tb);
    if (t0 > t1) return false;
  }
  if (axis0 < 0 || t0 <= 1e-9 || t0 >= t_max) return false;  // origin inside or too far
  Eigen::Vector3d n_local = Eigen::Vector3d::Zero();
  n_local[axis0] = sign0;
  hit.t = t0;
  hit.normal = Eigen::Vector3d(c * n_local.x() - s * n_local.y(), s * n_local.x() + c * n_local.y(),
                               n_local.z());
  const Eigen::Vector3d p = o + t0 * d;
  const int u = axis0 == 0 ? 1 : 0, v = axis0 == 2 ? 1 : 2;  // the two in-face axes
  hit.uv = Eigen::Vector2d(p[u] + b.half[u], p[v] + b.half[v]);
  return true;
}

bool intersect(const Cylinder& cyl, const Ray& ray, double t_max, Hit& hit) {
  const double ox = ray.origin.x() - cyl.center.x(), oy = ray.origin.y() - cyl.center.y();
  const double dx = ray.dir.x(), dy = ray.dir.y();
  const double a = dx * dx + dy * dy;
  bool found = false;
  if (a > 1e-12) {  // side wall
    const double b = ox * dx + oy * dy, cc = ox * ox + oy * oy - cyl.radius * cyl.radius;
    const double disc = b * b - a * cc;
    if (disc >= 0 && cc > 0) {  // origin outside the infinite cylinder
      const double t = (-b - std::sqrt(disc)) / a;
      const double z = ray.origin.z() + t * ray.dir.z();
      if (t > 1e-9 && t < t_max && z >= cyl.z0 && z <= cyl.z1) {
        hit.t = t;
        const double px = ox + t * dx, py = oy + t * dy;
        hit.normal = Eigen::Vector3d(px, py, 0) / cyl.radius;
        hit.uv = Eigen::Vector2d((std::atan2(py, px) + M_PI) * cyl.radius, z - cyl.z0);
        t_max = t;
        found = true;
      }
    }
  }
  if (std::abs(ray.dir.z()) > 1e-12) {  // top and bottom caps
    for (double zc : {cyl.z1, cyl.z0}) {
      const double t = (zc - ray.origin.z()) / ray.dir.z();
      if (t <= 1e-9 || t >= t_max) continue;
      const double px = ox + t * dx, py = oy + t * dy;
      if (px * px + py * py > cyl.radius * cyl.radius) continue;
      const bool top = zc == cyl.z1;
      if ((top && ray.dir.z() > 0) || (!top && ray.dir.z() < 0)) continue;  // seen from inside
      hit.t = t;
      hit.normal = Eigen::Vector3d(0, 0, top ? 1 : -1);
      hit.uv = Eigen::Vector2d(px, py);
      t_max = t;
      found = true;
    }
  }
  return found;
}

bool intersect(const Floor& f, const Ray& ray, double t_max, Hit& hit) {
  if (ray.dir.z() >= -1e-12 || ray.origin.z() <= f.z) return false;
  const double t = (f.z - ray.origin.z()) / ray.dir.z();
  if (t <= 1e-9 || t >= t_max) return false;
  const double x = ray.origin.x() + t * ray.dir.x(), y = ray.origin.y() + t * ray.dir.y();
  if (x < f.xmin || x > f.xmax || y < f.ymin || y > f.ymax) return false;
  hit.t = t;
  hit.normal = Eigen::Vector3d(0, 0, 1);
  hit.uv = Eigen::Vector2d(x, y);
  return true;
}

void boundingSphere(const Box& b, Eigen::Vector3d& c, double& r) {
  c = b.center;
  r = b.half.norm();
}

void boundingSphere(const Cylinder& cyl, Eigen::Vector3d& center, double& r) {
  center = Eigen::Vector3d(cyl.center.x(), cyl.center.y(), 0.5 * (cyl.z0 + cyl.z1));
  const double h = 0.5 * (cyl.z1 - cyl.z0);
  r = std::sqrt(cyl.radius * cyl.radius + h * h);
}

}  // namespace dynobj::sim
