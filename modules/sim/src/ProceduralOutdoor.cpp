// SPDX-License-Identifier: BSD-3-Clause
// Outdoor layouts: a street (facades with alleys, parked cars, trees, poles, hedges, railings,
// traffic both ways, cyclists, pedestrians; optionally a crossroad) and a plaza (buildings
// around, trees, bushes, benches, lamp posts, fences, a crowd). The parking lot is in
// ProceduralParking.cpp.
#include <cmath>
#include <stdexcept>

#include "WorldBuilder.h"

namespace dynobj::sim::detail {
namespace {

using V2 = Eigen::Vector2d;

const std::vector<std::string> kFacade{"posters", "posters", "checker", "noise", "stripes"};
const std::vector<std::string> kFences{"bars", "railing", "mesh"};

/// Buildings along a line y = y_face (facing the street towards -side·y) from x = a to b, with
/// random alleys between them; `skip` = |x| range kept open (a crossroad).
void facadeRow(WorldBuilder& w, double a, double b, double y_face, double side, double skip) {
  for (double x = a; x < b;) {
    const double len = std::min(w.uni(8, 30), b - x);
    const double mid = x + len / 2;
    if (std::abs(mid) > skip + len / 2 && len > 2) {
      const double setback = w.uni(0, 1.5), depth = 8, height = w.uni(6, 20);
      const std::string m = w.material(0.3, 0.6, kFacade, 1.5, 2.5);
      w.box(mid, y_face + side * (setback + depth / 2), len, depth, height, 0, m);
    }
    x += len + (w.chance(0.3) ? w.uni(3, 8) : 0.3);
  }
}

}  // namespace

void buildStreet(WorldBuilder& w) {
  const V2 size = w.size(140, 220, 0, 0);
  const double len = size.x(), road = w.uni(7, 10), walk = w.uni(3, 5);
  const double face = road / 2 + walk;  // facade line |y|
  const bool crossing = w.spec().crossing;
  const double skip = crossing ? face : -1e9;  // |x| kept free for the crossroad
  const double floor_albedo = w.uni(0.15, 0.25), floor_scale = w.uni(2.0, 3.0);
  w.floor(len + 40, crossing ? len + 40 : 2 * face + 40, floor_albedo, "markings", floor_scale);
  // Platform first: its lane stays clear.
  const std::string& route = w.spec().route;
  if (route == "auto" || route == "drive") {
    const std::vector<V2> pts{{-len / 2 + 8, -road / 4}, {len / 2 - 8, -road / 4}};
    w.platform(pts, w.platformSpeed(5.0), false, 2.0);  // a car: 2 m kept clear of others
    w.keepOut(pts, 1.5, false);
  } else if (route == "stationary" || route == "corner") {
    const V2 at = crossing ? V2(road / 2 + walk * 0.4, -road / 2 - walk * 0.4)
                           : V2(w.uni(-20, 20), -road / 2 - walk * 0.4);
    w.platformStationary(at, crossing ? 135 : 90);
    w.keepOut({at}, 1.2, false);
  } else {
    throw std::invalid_argument("route '" + route +
                                "' (this kind offers: drive, stationary, corner)");
  }
  for (double side : {-1.0, 1.0}) {
    facadeRow(w, -len / 2, len / 2, side * face, side, skip);
    for (double s : {-1.0, 1.0}) {  // kerbs (two halves), broken at a crossroad
      const double xa = s < 0 ? -len / 2 : (crossing ? face : 0);
      const double xb = s < 0 ? (crossing ? -face : 0) : len / 2;
      w.box(0.5 * (xa + xb), side * (road / 2 + 0.15), xb - xa, 0.3, 0.15, 0,
            "{albedo: 0.6, pattern: plain}");
    }
  }
  if (crossing)  // the cross street's facades
    for (double sx : {-1.0, 1.0})
      for (double sy : {-1.0, 1.0})
        for (int once = 0; once < 1; once++) {
          const double setback = w.uni(0, 1.5), height = w.uni(6, 20);
          const std::string m = w.material(0.3, 0.6, kFacade, 1.5, 2.5);
          w.box(sx * (face + 4 + setback), sy * (face + 25), 8, 40, height, 0, m);
        }
  // Parked cars in the parking strips, trees, lamp posts, hedges and railings.
  const double occupancy = w.uni(0.3, 0.7);
  for (double side : {-1.0, 1.0})
    for (double x = -len / 2 + 5; x < len / 2 - 5; x += 6.5)
      if (std::abs(x) > skip + 3 && w.chance(occupancy) &&
          w.isFree({x, side * (road / 2 - 1.1)}, 2.2))
        w.parkedCar(x, side * (road / 2 - 1.1),
                    w.chance(0.8) ? (side < 0 ? 0 : 180) : w.uni(-5, 5));
  const int trees = w.count(w.spec().trees, static_cast<int>(len / 25), static_cast<int>(len / 10));
  for (int k = 0; k < trees; k++) {
    const double side = w.chance(0.5) ? 1 : -1, x = w.uni(-len / 2, len / 2);
    const V2 p(x, side * (road / 2 + w.uni(0.8, 1.2)));
    if (std::abs(x) > skip + 2 && w.isFree(p, 1.0)) {
      const double height = w.uni(5, 10);
      w.tree(p.x(), p.y(), height, w.uni(1.5, 3.0));
    }
  }
  for (double x = -len / 2 + w.uni(0, 20); x < len / 2; x += w.uni(18, 30)) {
    const double side = w.chance(0.5) ? 1 : -1;
    const V2 p(x, side * (road / 2 + 0.5));
    if (std::abs(x) > skip && w.isFree(p, 0.3))
      w.cylinder(p.x(), p.y(), 0.1, w.uni(6, 8), "{albedo: 0.6, pattern: stripes, scale: 0.3}");
  }
  for (int k = w.count(w.spec().bushes, 3, 10); k > 0; k--) {  // hedges in front of facades
    const double side = w.chance(0.5) ? 1 : -1, l = w.uni(2, 8), x = w.uni(-len / 2, len / 2);
    const V2 p(x, side * (face - 0.6));
    if (std::abs(x) > skip + l / 2 && w.isFree(p, 0.5))
      w.bush(p.x(), p.y(), l, 0.8, w.uni(0.8, 1.6), 0, true);
  }
  for (int k = w.count(w.spec().fences, 2, 5); k > 0; k--) {  // railings along the kerb
    const double side = w.chance(0.5) ? 1 : -1, l = w.uni(4, 15), x = w.uni(-len / 2, len / 2 - l);
    const double y = side * (road / 2 + 0.45);
    if ((x > skip || x + l < -skip) && w.isFree({x + l / 2, y}, 0.3)) {
      const double height = w.uni(0.9, 1.2);
      w.fence({x, y}, {x + l, y}, height, kFences[static_cast<std::size_t>(w.uniInt(0, 2))]);
    }
  }
  // Traffic: cars both ways (and across at a crossroad), cyclists, pedestrians on the sidewalks.
  // A vehicle that would drive into the platform, another vehicle or someone standing is drawn
  // again (mover()).
  const int cars = w.count(w.spec().cars, 3, 8);
  for (int k = 0; k < cars; k++)
    for (int tries = 0; tries < 30; tries++) {
      // Keeping right both ways: down one lane, back up the other (turning beyond the ends).
      const double dir = w.chance(0.5) ? 1 : -1, y = dir > 0 ? -road / 4 : road / 4;
      const double end = len / 2 + 20;
      std::vector<V2> pts{{-dir * end, y}, {dir * end, y}, {dir * end, -y}, {-dir * end, -y}};
      if (crossing && k % 3 == 2)
        pts = {{-y, -dir * len / 2}, {-y, dir * len / 2}, {y, dir * len / 2}, {y, -dir * len / 2}};
      const double speed = w.uni(5, 12), phase = w.uni(0, 1);
      if (w.mover("car", WorldBuilder::loopFrom(pts, phase), speed, true, 0)) break;
    }
  for (int k = w.count(w.spec().cyclists, 1, 4); k > 0; k--)
    for (int tries = 0; tries < 30; tries++) {  // near the kerb, keeping right
      const double dir = w.chance(0.5) ? 1 : -1;
      const double y = dir > 0 ? -(road / 2 - 0.7) : road / 2 - 0.7, speed = w.uni(3, 6);
      const double end = len / 2 + 10;
      const std::vector<V2> loop{
          {-dir * end, y}, {dir * end, y}, {dir * end, -y}, {-dir * end, -y}};
      if (w.mover("cyclist", WorldBuilder::loopFrom(loop, w.uni(0, 1)), speed, true, 0)) break;
    }
  const int people = w.count(w.spec().pedestrians, 8, 20);
  for (int k = 0; k < people; k++) {
    const double side = w.chance(0.5) ? 1 : -1;
    const double y0 = side * (road / 2 + 0.5), y1 = side * (face - 0.3);
    const Eigen::Vector4d region(-len / 2 + 5, std::min(y0, y1), len / 2 - 5, std::max(y0, y1));
    V2 p;
    if (crossing && k % 5 == 4) {  // crossing the street at the crossroad, waiting in between
      const double speed = w.uni(0.9, 1.5), start = w.uni(0, 10);
      w.mover("pedestrian", {{-face + 1, side * (face - 1)}, {-face + 1, -side * (face - 1)}},
              speed, true, start, w.uni(2, 8));
    } else if (w.chance(w.spec().standing) &&
               w.freeSpot(region[0], region[1], region[2], region[3], 0.6, p))
      w.stander(p);
    else
      w.walker(region, 0.8, 1.6, 3.0);
  }
  // Dense traffic, only when asked (no draw otherwise: the scene stays the same). Riders in a
  // group share a lane and a speed, 2.2-3 m apart, every other one 0.35 m nearer the kerb.
  if (w.spec().rider_groups.lo > 0)
    for (int g = w.count(w.spec().rider_groups, 0, 0); g > 0; g--)
      for (int tries = 0; tries < 30; tries++) {
        const double dir = w.chance(0.5) ? 1 : -1, speed = w.uni(3, 9), phase = w.uni(0, 1);
        // The first rider s0 metres down the first straight (where the lanes of the riders,
        // 0.7 m apart, are equally long).
        const double end = len / 2 + 10, s0 = 20 + phase * (2 * end - 20);
        const int riders = w.uniInt(3, 6);
        double along = 0;  // behind the first rider, along the lane [m]
        int added = 0;
        for (int i = 0; i < riders; i++) {
          const double kerb = road / 2 - (i % 2 ? 0.55 : 0.9);  // |y| of this rider's line
          const double y = dir > 0 ? -kerb : kerb;
          const std::vector<V2> loop{
              {-dir * end, y}, {dir * end, y}, {dir * end, -y}, {-dir * end, -y}};
          const double at = (s0 - along) / (4 * end + 4 * std::abs(y));
          added +=
              w.mover("cyclist", WorldBuilder::loopFrom(loop, at - std::floor(at)), speed, true, 0);
          along += w.uni(2.2, 3.0);
        }
        if (added >= 2) break;
      }
  // Two-wheelers parked on the sidewalk by the kerb (a scooter or motorcycle: 1.9 x 0.7 x 1.1 m),
  // 60 % with someone standing beside.
  if (w.spec().two_wheelers.lo > 0)
    for (int k = w.count(w.spec().two_wheelers, 0, 0); k > 0; k--) {
      const double side = w.chance(0.5) ? 1 : -1, x = w.uni(-len / 2 + 5, len / 2 - 5);
      const V2 p(x, side * (road / 2 + 1.6));
      if (!w.isFree(p, 1.0)) continue;
      const double yaw = w.uni(-20, 20) + (w.chance(0.5) ? 0 : 90), c = std::cos(yaw * M_PI / 180),
                   sn = std::sin(yaw * M_PI / 180);
      w.box(p.x(), p.y(), 1.9, 0.7, 1.1, yaw, w.material(0.1, 0.4, {"noise", "plain"}, 0.1, 0.3));
      // Beside its long side, 0.35-0.6 m off it.
      const double u = w.uni(-0.5, 0.5), v = (w.chance(0.5) ? 1 : -1) * (0.35 + w.uni(0.35, 0.6));
      if (w.chance(0.6)) w.stander({p.x() + c * u - sn * v, p.y() + sn * u + c * v});
    }
}

void buildPlaza(WorldBuilder& w) {
  const V2 size = w.size(35, 60, 30, 50);
  const double sx = size.x(), sy = size.y();
  const double floor_albedo = w.uni(0.2, 0.35);
  const char* floor_pattern = w.chance(0.5) ? "checker" : "markings";
  w.floor(sx + 40, sy + 40, floor_albedo, floor_pattern, w.uni(0.6, 1.5));
  // Buildings around, broken by streets leading out.
  for (double side : {-1.0, 1.0}) {
    for (double x = -sx / 2 - 10; x < sx / 2 + 10;) {
      const double l = w.uni(8, 25);
      if (!w.chance(0.2)) {
        const double height = w.uni(8, 20);
        w.box(x + l / 2, side * (sy / 2 + 5), l, 10, height, 0,
              w.material(0.3, 0.6, kFacade, 1.5, 2.5));
      }
      x += l + (w.chance(0.35) ? w.uni(6, 10) : 0.2);
    }
    for (double y = -sy / 2; y < sy / 2;) {
      const double l = w.uni(8, 25);
      if (!w.chance(0.2)) {
        const double height = w.uni(8, 20);
        w.box(side * (sx / 2 + 5), y + l / 2, 10, l, height, 0,
              w.material(0.3, 0.6, kFacade, 1.5, 2.5));
      }
      y += l + (w.chance(0.35) ? w.uni(6, 10) : 0.2);
    }
  }
  // Platform: across the plaza and back (or standing, or a loop).
  const std::string& route = w.spec().route;
  const double ax = sx / 2 - 4, ay = sy / 2 - 4;
  std::vector<V2> pts;
  if (route == "auto" || route == "cross") {
    pts = {{-ax, w.uni(-ay, ay) * 0.5}, {ax, w.uni(-ay, ay) * 0.5}};
    if (w.chance(0.5)) std::swap(pts[0], pts[1]);
  } else if (route == "loop") {
    pts = {{-ax, -ay}, {ax, -ay}, {ax, ay}, {-ax, ay}};
  } else if (route == "stationary") {
    pts = {{w.uni(-ax, ax) * 0.5, w.uni(-ay, ay) * 0.5}};
  } else {
    throw std::invalid_argument("route '" + route +
                                "' (this kind offers: cross, loop, stationary)");
  }
  if (pts.size() == 1)
    w.platformStationary(pts[0], w.uni(-180, 180), 0.8);
  else
    w.platform(pts, w.platformSpeed(1.0), true);
  w.keepOut(pts, pts.size() == 1 ? 1.5 : 1.8, route == "loop");
  // Furniture and vegetation.
  const double mx = sx / 2 - 1.5, my = sy / 2 - 1.5;
  V2 p;
  if (w.chance(0.5) && w.freeSpot(-sx / 4, -sy / 4, sx / 4, sy / 4, 4.0, p)) {  // a fountain
    const double r = w.uni(2, 3.5);
    w.cylinder(p.x(), p.y(), r, w.uni(0.5, 0.8), "{albedo: 0.55, pattern: noise, scale: 0.3}");
  }
  for (int k = w.count(w.spec().trees, 5, 12); k > 0; k--)
    if (w.freeSpot(-mx, -my, mx, my, 1.5, p)) {
      const double height = w.uni(5, 11);
      w.tree(p.x(), p.y(), height, w.uni(1.5, 3.5));
    }
  for (int k = w.count(w.spec().bushes, 4, 10); k > 0; k--) {
    const double a = w.uni(0.8, 3.0), b = w.uni(0.8, 2.0);
    if (!w.freeSpot(-mx, -my, mx, my, 0.6 * std::hypot(a, b), p)) continue;
    const bool hedge = w.chance(0.3);
    const double height = w.uni(0.6, 1.5);
    w.bush(p.x(), p.y(), a, b, height, w.uni(0, 180), hedge);
    if (w.chance(0.3)) {  // a low railing around the bed
      const V2 f(p.x() - a / 2 - 0.5, p.y() + b / 2 + 0.5),
          g(p.x() + a / 2 + 0.5, p.y() + b / 2 + 0.5);
      if (w.isFree(0.5 * (f + g), 0.2)) w.fence(f, g, w.uni(0.4, 0.8), "railing");
    }
  }
  for (int k = w.uniInt(3, 8); k > 0; k--)  // benches
    if (w.freeSpot(-mx, -my, mx, my, 1.2, p)) {
      const double yaw = w.uni(0, 180);
      w.box(p.x(), p.y(), 1.8, 0.5, 0.45, yaw,
            w.material(0.3, 0.6, {"stripes", "noise"}, 0.1, 0.2));
    }
  for (int k = w.uniInt(4, 10); k > 0; k--)  // lamp posts
    if (w.freeSpot(-mx, -my, mx, my, 0.5, p))
      w.cylinder(p.x(), p.y(), 0.08, w.uni(4, 6), "{albedo: 0.5, pattern: stripes, scale: 0.4}");
  for (int k = w.count(w.spec().fences, 1, 3); k > 0; k--) {
    const double l = w.uni(4, 12), yaw = w.chance(0.5) ? 0 : M_PI / 2;
    const V2 d(std::cos(yaw) * l / 2, std::sin(yaw) * l / 2);
    if (w.freeSpot(-mx + l / 2, -my + l / 2, mx - l / 2, my - l / 2, l / 2, p)) {
      const double height = w.uni(0.9, 1.8);
      w.fence(p - d, p + d, height, kFences[static_cast<std::size_t>(w.uniInt(0, 2))]);
    }
  }
  // People (a crowd when asked), a few cyclists across.
  const int people = w.count(w.spec().pedestrians, 10, 25);
  const Eigen::Vector4d region(-sx / 2 + 2, -sy / 2 + 2, sx / 2 - 2, sy / 2 - 2);
  for (int k = 0; k < people; k++)
    if (w.chance(w.spec().standing) &&
        w.freeSpot(region[0], region[1], region[2], region[3], 0.6, p))
      w.stander(p);
    else
      w.walker(region, 0.6, 1.6, 4.0, w.chance(0.15) ? w.uni(3, 0.5 * w.duration()) : 0.0);
  for (int k = w.count(w.spec().cyclists, 0, 3); k > 0; k--)
    for (int tries = 0; tries < 10; tries++) {  // not through the platform or others (mover())
      const double y0 = w.uni(-ay, ay), y1 = w.uni(-ay, ay), dir = w.chance(0.5) ? 1 : -1;
      const double speed = w.uni(3, 5.5);
      if (w.mover("cyclist", {{-dir * (sx / 2 + 8), y0}, {dir * (sx / 2 + 8), y1}}, speed, true,
                  w.uni(0, 0.5 * w.duration())))
        break;
    }
}

}  // namespace dynobj::sim::detail
