// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/Procedural.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "WorldBuilder.h"

namespace dynobj::sim {

ProceduralSpec::Kind ProceduralSpec::kindFromString(const std::string& name) {
  if (name == "street") return Kind::Street;
  if (name == "plaza") return Kind::Plaza;
  if (name == "room") return Kind::Room;
  if (name == "parking") return Kind::Parking;
  if (name == "warehouse") return Kind::Warehouse;
  throw std::invalid_argument("unknown kind '" + name +
                              "' (street, plaza, room, parking, warehouse)");
}

std::string generateWorld(const ProceduralSpec& spec, std::uint32_t seed, double duration) {
  detail::WorldBuilder w(spec, seed, duration);
  switch (spec.kind) {
    case ProceduralSpec::Kind::Street:
      detail::buildStreet(w);
      break;
    case ProceduralSpec::Kind::Plaza:
      detail::buildPlaza(w);
      break;
    case ProceduralSpec::Kind::Room:
      detail::buildRoom(w);
      break;
    case ProceduralSpec::Kind::Parking:
      detail::buildParking(w);
      break;
    case ProceduralSpec::Kind::Warehouse:
      detail::buildWarehouse(w);
      break;
  }
  return w.yaml();
}

namespace detail {

WorldBuilder::WorldBuilder(const ProceduralSpec& spec, std::uint32_t seed, double duration)
    : spec_(spec),
      duration_(duration),
      rng_(seed * 2654435761u + 97u * static_cast<std::uint32_t>(spec.kind) + 12345u) {}

double WorldBuilder::uni(double lo, double hi) {
  return hi > lo ? std::uniform_real_distribution<double>(lo, hi)(rng_) : lo;
}

int WorldBuilder::uniInt(int lo, int hi) {
  return hi > lo ? std::uniform_int_distribution<int>(lo, hi)(rng_) : lo;
}

int WorldBuilder::count(const ProceduralSpec::Count& c, int def_lo, int def_hi) {
  return c.lo >= 0 ? uniInt(c.lo, std::max(c.lo, c.hi)) : uniInt(def_lo, def_hi);
}

Eigen::Vector2d WorldBuilder::size(double xlo, double xhi, double ylo, double yhi) {
  const double x = uni(xlo, xhi), y = uni(ylo, yhi);  // always drawn: same stream either way
  return {spec_.size.x() > 0 ? spec_.size.x() : x, spec_.size.y() > 0 ? spec_.size.y() : y};
}

void WorldBuilder::keepOut(const std::vector<Eigen::Vector2d>& path, double half_width,
                           bool closed) {
  for (std::size_t i = 0; i + 1 < path.size(); i++)
    corridors_.push_back({path[i], path[i + 1], half_width});
  if (closed && path.size() > 2) corridors_.push_back({path.back(), path.front(), half_width});
  if (path.size() == 1) occupied_.push_back({path[0], half_width});
}

bool WorldBuilder::isFree(const Eigen::Vector2d& p, double r) const {
  for (const Disc& d : occupied_)
    if ((p - d.c).norm() < r + d.r) return false;
  for (const Corridor& c : corridors_) {
    const Eigen::Vector2d ab = c.b - c.a;
    const double len2 = ab.squaredNorm();
    const double s = len2 > 0 ? std::clamp((p - c.a).dot(ab) / len2, 0.0, 1.0) : 0.0;
    if ((p - (c.a + s * ab)).norm() < r + c.half_width) return false;
  }
  return true;
}

bool WorldBuilder::freeSpot(double xmin, double ymin, double xmax, double ymax, double r,
                            Eigen::Vector2d& out, int tries) {
  for (int k = 0; k < tries; k++) {
    const Eigen::Vector2d p(uni(xmin, xmax), uni(ymin, ymax));
    if (isFree(p, r)) {
      out = p;
      return true;
    }
  }
  return false;
}

std::string WorldBuilder::num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3f", std::abs(v) < 5e-4 ? 0.0 : v);
  return buf;
}

std::string WorldBuilder::point(const Eigen::Vector2d& p) {
  return "[" + num(p.x()) + ", " + num(p.y()) + "]";
}

std::string WorldBuilder::material(double lo, double hi, const std::vector<std::string>& patterns,
                                   double slo, double shi) {
  const double albedo = uni(lo, hi);
  const std::string& pattern =
      patterns[static_cast<std::size_t>(uniInt(0, static_cast<int>(patterns.size()) - 1))];
  return "{albedo: " + num(albedo) + ", pattern: " + pattern + ", scale: " + num(uni(slo, shi)) +
         "}";
}

void WorldBuilder::floor(double sx, double sy, double albedo, const std::string& pattern,
                         double scale) {
  floor_ << "floor: {size: [" << num(sx) << ", " << num(sy)
         << "], material: {albedo: " << num(albedo) << ", pattern: " << pattern
         << ", scale: " << num(scale) << "}}\n";
}

void WorldBuilder::box(double cx, double cy, double sx, double sy, double sz, double yaw_deg,
                       const std::string& material, double z0) {
  static_ << "  - {box: {center: [" << num(cx) << ", " << num(cy) << ", " << num(z0 + sz / 2)
          << "], size: [" << num(sx) << ", " << num(sy) << ", " << num(sz)
          << "], yaw_deg: " << num(yaw_deg) << "}, material: " << material << "}\n";
  const double r = 0.5 * std::hypot(sx, sy);
  if (r < 3.0) occupied_.push_back({{cx, cy}, r});
}

void WorldBuilder::cylinder(double cx, double cy, double r, double h, const std::string& material) {
  static_ << "  - {cylinder: {center: [" << num(cx) << ", " << num(cy) << "], radius: " << num(r)
          << ", height: " << num(h) << "}, material: " << material << "}\n";
  occupied_.push_back({{cx, cy}, r});
}

void WorldBuilder::parkedCar(double cx, double cy, double yaw_deg) {
  static_ << "  - {car: {center: [" << num(cx) << ", " << num(cy) << "], yaw_deg: " << num(yaw_deg)
          << "}, material: " << material(0.15, 0.7, {"noise", "plain"}, 0.3, 0.8) << "}\n";
  occupied_.push_back({{cx, cy}, 2.3});
}

void WorldBuilder::tree(double cx, double cy, double h, double crown_r) {
  static_ << "  - {tree: {center: [" << num(cx) << ", " << num(cy) << "], height: " << num(h)
          << ", trunk_radius: " << num(uni(0.1, 0.25)) << ", crown_radius: " << num(crown_r)
          << ", crown_height: " << num(uni(0.45, 0.65) * h) << ", density: " << num(uni(0.8, 2.0))
          << ", sway: " << num(uni(0.02, 0.08)) << ", sway_hz: " << num(uni(0.2, 0.5))
          << "}, foliage: {albedo: " << num(uni(0.1, 0.22)) << "}}\n";
  occupied_.push_back({{cx, cy}, 0.4});  // the trunk; walkers pass under the crown
}

void WorldBuilder::bush(double cx, double cy, double sx, double sy, double sz, double yaw_deg,
                        bool hedge) {
  static_ << "  - {bush: {center: [" << num(cx) << ", " << num(cy) << "], size: [" << num(sx)
          << ", " << num(sy) << ", " << num(sz) << "], yaw_deg: " << num(yaw_deg)
          << ", shape: " << (hedge ? "box" : "ellipsoid") << ", density: " << num(uni(1.5, 4.0))
          << "}, material: {albedo: " << num(uni(0.1, 0.22)) << "}}\n";
  occupied_.push_back({{cx, cy}, 0.5 * std::hypot(sx, sy)});
}

void WorldBuilder::fence(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double h,
                         const std::string& style) {
  static_ << "  - {fence: {from: " << point(a) << ", to: " << point(b) << ", height: " << num(h)
          << ", style: " << style << "}, material: {albedo: " << num(uni(0.3, 0.7))
          << ", pattern: plain}}\n";
  const double len = (b - a).norm();
  for (double s = 0; s <= len; s += 0.5) occupied_.push_back({a + (b - a) * (s / len), 0.3});
}

void WorldBuilder::walker(const Eigen::Vector4d& region, double speed_lo, double speed_hi,
                          double pause_hi, double start) {
  actors_ << "  - {class: pedestrian, height: [1.5, 1.95], trajectory: {type: random_walk, "
             "region: ["
          << num(region[0]) << ", " << num(region[1]) << ", " << num(region[2]) << ", "
          << num(region[3]) << "], speed: [" << num(speed_lo) << ", " << num(speed_hi)
          << "], pause: [0, " << num(pause_hi) << "], start: " << num(start) << "}}\n";
}

void WorldBuilder::stander(const Eigen::Vector2d& at) {
  actors_ << "  - {class: pedestrian, height: [1.55, 1.9], trajectory: {type: stationary, at: "
          << point(at) << ", yaw_deg: " << num(uni(-180, 180)) << "}}\n";
  occupied_.push_back({at, kStanderRadius});
  standers_.push_back(at);
}

namespace {
/// A vehicle's footprint (half length hl along its yaw, half width hw) as three discs of radius
/// hw along its axis.
std::array<Eigen::Vector2d, 3> footprint(const Pose2& p, double hl, double hw) {
  const Eigen::Vector2d axis(std::cos(p.yaw), std::sin(p.yaw)), c(p.x, p.y);
  const double off = std::max(hl - hw, 0.0);
  return {c - off * axis, c, c + off * axis};
}
}  // namespace

bool WorldBuilder::clearOfOthers(const PoseTrack& track, double hl, double hw, double start) const {
  constexpr double kGap = 0.1;  // [m] between two vehicles' footprints, or one and a person
  for (double t = 0; t <= duration_; t += 0.05) {
    const Pose2 a = track.at(t);
    if (platform_radius_ > 0) {  // the platform: its radius from the footprint rectangle
      const Pose2 p = platform_track_.at(t);
      const double dx = p.x - a.x, dy = p.y - a.y, c = std::cos(a.yaw), s = std::sin(a.yaw);
      const double lx = std::max(std::abs(c * dx + s * dy) - hl, 0.0);
      const double ly = std::max(std::abs(-s * dx + c * dy) - hw, 0.0);
      if (std::hypot(lx, ly) < platform_radius_) return false;
    }
    const auto mine = footprint(a, hl, hw);
    for (const Eigen::Vector2d& at : standers_)
      for (const Eigen::Vector2d& d : mine)
        if ((d - at).norm() < hw + kStanderRadius + kGap) return false;
    for (const Vehicle& v : vehicles_) {
      if (t < start && t < v.start) continue;  // both still waiting to set off (off-stage)
      const auto theirs = footprint(v.track.at(t), v.hl, v.hw);
      for (const Eigen::Vector2d& d : mine)
        for (const Eigen::Vector2d& e : theirs)
          if ((d - e).norm() < hw + v.hw + kGap) return false;
    }
  }
  return true;
}

std::vector<Eigen::Vector2d> WorldBuilder::loopFrom(const std::vector<Eigen::Vector2d>& pts,
                                                    double phase) {
  double total = 0;
  for (std::size_t i = 0; i < pts.size(); i++) total += (pts[(i + 1) % pts.size()] - pts[i]).norm();
  double at = phase * total;
  for (std::size_t i = 0; i < pts.size(); i++) {
    const Eigen::Vector2d a = pts[i], b = pts[(i + 1) % pts.size()];
    const double l = (b - a).norm();
    if (at <= l || i + 1 == pts.size()) {
      std::vector<Eigen::Vector2d> out{a + (b - a) * (l > 0 ? std::min(at / l, 1.0) : 0.0)};
      for (std::size_t j = 1; j <= pts.size(); j++) out.push_back(pts[(i + j) % pts.size()]);
      return out;
    }
    at -= l;
  }
  return pts;
}

bool WorldBuilder::mover(const std::string& cls, const std::vector<Eigen::Vector2d>& pts,
                         double speed, bool loop, double start, double pause) {
  if (cls != "pedestrian") {  // vehicles keep clear of the sensor, each other and standers
    const double hl = cls == "car" ? 2.2 : 0.85, hw = cls == "car" ? 0.9 : 0.3;  // half footprint
    PoseTrack track = PoseTrack::waypoints(pts, speed, pause, loop, start, duration_);
    if (!clearOfOthers(track, hl, hw, start)) return false;
    vehicles_.push_back({std::move(track), hl, hw, start});
    keepOut(pts, hw + kStanderRadius, loop);  // no one placed later stands in its way
  }
  actors_ << "  - {class: " << cls << ", trajectory: {type: waypoints, speed: " << num(speed)
          << ", pause: " << num(pause) << ", loop: " << (loop ? "true" : "false")
          << ", start: " << num(start) << ", points: [";
  for (std::size_t i = 0; i < pts.size(); i++) actors_ << (i ? ", " : "") << point(pts[i]);
  actors_ << "]}}\n";
  return true;
}

void WorldBuilder::platform(const std::vector<Eigen::Vector2d>& pts, double speed, bool loop,
                            double radius) {
  platform_track_ = PoseTrack::waypoints(pts, speed, 0.0, loop, 0.0, duration_);
  platform_radius_ = radius;
  platform_ << "platform:\n  trajectory: {type: waypoints, speed: " << num(speed)
            << ", loop: " << (loop ? "true" : "false") << ", points: [";
  for (std::size_t i = 0; i < pts.size(); i++) platform_ << (i ? ", " : "") << point(pts[i]);
  platform_ << "]}\n";
}

void WorldBuilder::platformStationary(const Eigen::Vector2d& at, double yaw_deg, double radius) {
  platform_track_ = PoseTrack::stationary({at.x(), at.y(), yaw_deg * M_PI / 180});
  platform_radius_ = radius;
  platform_ << "platform:\n  trajectory: {type: stationary, at: " << point(at)
            << ", yaw_deg: " << num(yaw_deg) << "}\n";
}

std::string WorldBuilder::yaml() const {
  std::string out = "# generated by dynobj-sim (procedural world)\n" + floor_.str();
  const std::string st = static_.str(), ac = actors_.str();
  out += st.empty() ? "static: []\n" : "static:\n" + st;
  out += ac.empty() ? "actors: []\n" : "actors:\n" + ac;
  return out + platform_.str();
}

}  // namespace detail
}  // namespace dynobj::sim
