// SPDX-License-Identifier: BSD-3-Clause
// Ray casting against the see-through clutter of Shapes.h: porous foliage volumes and fences.
#include <algorithm>
#include <cmath>
#include <limits>

#include "dynobj/sim/Shapes.h"

namespace dynobj::sim {

std::uint64_t splitMix64(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ULL);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double uniform01(std::uint64_t& state) {
  return static_cast<double>(splitMix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

bool intersect(const Porous& v, const Ray& ray, double t_max, std::uint64_t key, Hit& hit) {
  if (!(v.density > 0)) return false;
  // Into the volume frame (rotation about Z by -yaw).
  const double c = std::cos(v.yaw), s = std::sin(v.yaw);
  const Eigen::Vector3d d0 = ray.origin - v.center;
  const Eigen::Vector3d o(c * d0.x() + s * d0.y(), -s * d0.x() + c * d0.y(), d0.z());
  const Eigen::Vector3d d(c * ray.dir.x() + s * ray.dir.y(), -s * ray.dir.x() + c * ray.dir.y(),
                          ray.dir.z());
  double t0 = -std::numeric_limits<double>::infinity(),
         t1 = std::numeric_limits<double>::infinity();
  if (v.ellipsoid) {  // unit sphere after scaling by the semi-axes
    const Eigen::Vector3d os = o.cwiseQuotient(v.half), ds = d.cwiseQuotient(v.half);
    const double a = ds.squaredNorm(), b = os.dot(ds), cc = os.squaredNorm() - 1.0;
    const double disc = b * b - a * cc;
    if (a < 1e-18 || disc < 0) return false;
    const double sq = std::sqrt(disc);
    t0 = (-b - sq) / a;
    t1 = (-b + sq) / a;
  } else {
    for (int k = 0; k < 3; k++) {
      if (std::abs(d[k]) < 1e-12) {
        if (o[k] < -v.half[k] || o[k] > v.half[k]) return false;
        continue;
      }
      double ta = (-v.half[k] - o[k]) / d[k], tb = (v.half[k] - o[k]) / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t0 > t1) return false;
  }
  t0 = std::max(t0, 0.0);  // the sensor may stand inside the foliage
  t1 = std::min(t1, t_max);
  if (t1 <= t0) return false;
  std::uint64_t state = key;
  const double depth = -std::log1p(-uniform01(state)) / v.density;  // exponential, rate density
  const double t = t0 + depth;
  if (t >= t1 || t <= 1e-9) return false;
  // A leaf at a random orientation, facing the sensor; its own reflectivity.
  const double nz = 2.0 * uniform01(state) - 1.0, phi = 2.0 * M_PI * uniform01(state);
  const double nr = std::sqrt(std::max(0.0, 1.0 - nz * nz));
  Eigen::Vector3d n(nr * std::cos(phi), nr * std::sin(phi), nz);
  if (n.dot(ray.dir) > 0) n = -n;
  hit.t = t;
  hit.normal = n;
  const Eigen::Vector3d p = ray.origin + t * ray.dir;
  hit.uv = Eigen::Vector2d(p.x() + p.y(), p.z());
  hit.gain = 0.25 + 1.5 * uniform01(state);
  return true;
}

bool intersect(const Fence& f, const Ray& ray, double t_max, Hit& hit) {
  const Eigen::Vector2d ab = f.b - f.a;
  const double len = ab.norm();
  if (len < 1e-9) return false;
  const Eigen::Vector2d u = ab / len, n(-u.y(), u.x());
  const double denom = ray.dir.x() * n.x() + ray.dir.y() * n.y();
  if (std::abs(denom) < 1e-12) return false;  // parallel to the panel
  const double t =
      ((f.a.x() - ray.origin.x()) * n.x() + (f.a.y() - ray.origin.y()) * n.y()) / denom;
  if (t <= 1e-9 || t >= t_max) return false;
  const Eigen::Vector3d p = ray.origin + t * ray.dir;
  const double along = (p.x() - f.a.x()) * u.x() + (p.y() - f.a.y()) * u.y();
  const double z = p.z();
  if (along < 0 || along > len || z < f.z0 || z > f.z1) return false;
  bool solid = false;
  if (f.bar_spacing > 0) {
    const double k = std::round(along / f.bar_spacing);
    const double dist = std::min(std::abs(along - k * f.bar_spacing), len - along);
    solid = dist <= 0.5 * f.bar_width;
  }
  for (int i = 0; i < std::min<int>(f.rail_count, static_cast<int>(f.rails.size())) && !solid; i++)
    solid = std::abs(z - f.rails[static_cast<std::size_t>(i)]) <= 0.5 * f.rail_width;
  if (!solid && f.rail_spacing > 0) {
    const double h = z - f.z0, k = std::round(h / f.rail_spacing);
    solid = std::abs(h - k * f.rail_spacing) <= 0.5 * f.rail_width;
  }
  if (!solid) return false;
  hit.t = t;
  hit.normal = denom < 0 ? Eigen::Vector3d(n.x(), n.y(), 0) : Eigen::Vector3d(-n.x(), -n.y(), 0);
  hit.uv = Eigen::Vector2d(along, z - f.z0);
  return true;
}

void boundingSphere(const Porous& v, Eigen::Vector3d& center, double& r) {
  center = v.center;
  r = v.ellipsoid ? v.half.maxCoeff() : v.half.norm();
}

void boundingSphere(const Fence& f, Eigen::Vector3d& center, double& r) {
  const Eigen::Vector2d m = 0.5 * (f.a + f.b);
  center = Eigen::Vector3d(m.x(), m.y(), 0.5 * (f.z0 + f.z1));
  r = std::hypot(0.5 * (f.b - f.a).norm(), 0.5 * (f.z1 - f.z0));
}

}  // namespace dynobj::sim
