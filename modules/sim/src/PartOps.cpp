// SPDX-License-Identifier: BSD-3-Clause
#include "PartOps.h"

#include <algorithm>
#include <cmath>

namespace dynobj::sim::detail {

Part placed(const Part& p, const Pose2& pose) {
  Part out = p;
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  if (p.kind == Part::Kind::Box) {
    const Eigen::Vector3d& l = p.box.center;
    out.box.center = {pose.x + c * l.x() - s * l.y(), pose.y + s * l.x() + c * l.y(), l.z()};
    out.box.yaw = p.box.yaw + pose.yaw;
  } else {
    const Eigen::Vector2d& l = p.cylinder.center;
    out.cylinder.center = {pose.x + c * l.x() - s * l.y(), pose.y + s * l.x() + c * l.y()};
  }
  return out;
}

namespace {

/// Random key of one ray against one part: a hash of the sweep's and pixel's key and the part.
std::uint64_t partKey(std::uint64_t pixel_key, std::uint32_t uid) {
  std::uint64_t st = pixel_key ^ (static_cast<std::uint64_t>(uid) * 0xA24BAED4963EE407ULL);
  return splitMix64(st);
}

}  // namespace

bool intersectPart(const Part& p, const Ray& ray, double t_max, std::uint64_t pixel_key,
                   std::uint32_t uid, Hit& hit) {
  bool found = false;
  switch (p.kind) {
    case Part::Kind::Box:
      found = intersect(p.box, ray, t_max, hit);
      break;
    case Part::Kind::Cylinder:
      found = intersect(p.cylinder, ray, t_max, hit);
      break;
    case Part::Kind::Porous:
      return intersect(p.porous, ray, t_max, partKey(pixel_key, uid), hit);
    case Part::Kind::Fence:
      found = intersect(p.fence, ray, t_max, hit);
      break;
  }
  if (found) hit.gain = 1.0;  // solid surfaces: the material's own reflectivity
  return found;
}

/// Foliage swaying in the wind: the crown's centre moves on a slow Lissajous curve of amplitude
/// `sway` [m], its phase fixed per part.
Part swayed(const Part& p, double t, std::uint32_t uid) {
  if (p.kind != Part::Kind::Porous || p.sway <= 0) return p;
  std::uint64_t st = 0x5A5A5A5AULL + uid;
  const double ph1 = 2 * M_PI * uniform01(st), ph2 = 2 * M_PI * uniform01(st);
  const double w = 2 * M_PI * p.sway_hz * t;
  Part out = p;
  out.porous.center.x() += p.sway * std::sin(w + ph1);
  out.porous.center.y() += p.sway * std::sin(0.83 * w + ph2);
  return out;
}

Part swung(const Part& p, double t, double speed, int actor) {
  if (p.swing == 0 || p.kind != Part::Kind::Cylinder) return p;
  std::uint64_t st = 0x6A17ULL + static_cast<std::uint64_t>(actor);
  const double phase = 2 * M_PI * uniform01(st);
  const double stride = std::min(1.0, speed / 1.4);
  Part out = p;
  out.cylinder.center.x() += p.swing * stride * std::sin(2 * M_PI * 0.9 * t + phase);
  return out;
}

void boundingSphere(const Part& p, Eigen::Vector3d& center, double& r) {
  switch (p.kind) {
    case Part::Kind::Box:
      return sim::boundingSphere(p.box, center, r);
    case Part::Kind::Cylinder:
      return sim::boundingSphere(p.cylinder, center, r);
    case Part::Kind::Porous:
      return sim::boundingSphere(p.porous, center, r);
    case Part::Kind::Fence:
      return sim::boundingSphere(p.fence, center, r);
  }
}

}  // namespace dynobj::sim::detail
