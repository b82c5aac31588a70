// SPDX-License-Identifier: BSD-3-Clause
// Indoor layouts: a room (hall, concourse: walls, pillars, crates, a crowd) and a warehouse
// (rack rows with aisles, pallets, workers in the aisles, forklift-sized vehicles).
#include <cmath>
#include <stdexcept>

#include "WorldBuilder.h"

namespace dynobj::sim::detail {
namespace {

using V2 = Eigen::Vector2d;

void walls(WorldBuilder& w, double sx, double sy, double h) {
  const std::vector<std::string> wall_patterns{"posters", "posters", "checker", "stripes", "noise"};
  for (int k = 0; k < 4; k++) {
    const std::string m = w.material(0.35, 0.6, wall_patterns, 0.8, 1.6);
    if (k < 2)
      w.box(0, (k ? -1 : 1) * sy / 2, sx + 0.4, 0.4, h, 0, m);
    else
      w.box((k == 2 ? 1 : -1) * sx / 2, 0, 0.4, sy, h, 0, m);
  }
}

/// Platform route: a loop `inset` metres inside the walls (random corner and direction), or the
/// spec's alternatives.
void roomRoute(WorldBuilder& w, double sx, double sy, double inset, double speed) {
  const std::string& route = w.spec().route;
  const double ax = sx / 2 - inset, ay = sy / 2 - inset;
  if (route == "stationary") {
    const V2 at{w.uni(-ax, ax), w.uni(-ay, ay)};
    const double yaw = w.uni(-180, 180);
    w.platformStationary(at, yaw);
    w.keepOut({at}, 1.5, false);
    return;
  }
  std::vector<V2> pts;
  if (route == "auto" || route == "loop") {
    pts = {{-ax, -ay}, {ax, -ay}, {ax, ay}, {-ax, ay}};
    const int first = w.uniInt(0, 3);
    std::rotate(pts.begin(), pts.begin() + first, pts.end());
    if (w.chance(0.5)) std::reverse(pts.begin(), pts.end());
  } else if (route == "cross") {
    pts = {{-ax, w.uni(-ay, ay)}, {ax, w.uni(-ay, ay)}};
  } else {
    throw std::invalid_argument("route '" + route +
                                "' (this kind offers: loop, cross, stationary)");
  }
  w.platform(pts, speed, true);
  w.keepOut(pts, 1.3, route != "cross");
}

}  // namespace

void buildRoom(WorldBuilder& w) {
  const V2 size = w.size(22, 40, 14, 28);
  const double sx = size.x(), sy = size.y(), h = w.uni(4, 7);
  const double floor_albedo = w.uni(0.2, 0.3), floor_scale = w.uni(1.0, 2.0);
  w.floor(sx + 4, sy + 4, floor_albedo, "markings", floor_scale);
  walls(w, sx, sy, h);
  const double inset = w.uni(3.5, 5.0);
  roomRoute(w, sx, sy, inset, w.platformSpeed(1.0));
  // Pillars on a grid, some missing.
  const double pitch = w.uni(6, 10);
  const std::string pillar = w.material(0.45, 0.7, {"stripes", "checker", "noise"}, 0.3, 0.5);
  const bool round = w.chance(0.5);
  for (double x = -sx / 2 + pitch; x < sx / 2 - 2; x += pitch)
    for (double y = -sy / 2 + pitch; y < sy / 2 - 2; y += pitch) {
      if (!w.chance(0.6) || !w.isFree({x, y}, 0.9)) continue;
      if (round)
        w.cylinder(x, y, 0.4, h, pillar);
      else
        w.box(x, y, 0.8, 0.8, h, 0, pillar);
    }
  // Crates, shelves and counters along the walls, a few boxes in the open.
  const int crates = w.uniInt(6, 12);
  for (int k = 0; k < crates; k++) {
    const double lx = w.uni(0.8, 3.0), ly = w.uni(0.6, 1.5), lz = w.uni(0.6, 2.2);
    const int side = w.uniInt(0, 3);
    const double off = w.uni(0.4, 1.5) + ly / 2;
    const double along = side < 2 ? w.uni(-sx / 2 + 2, sx / 2 - 2) : w.uni(-sy / 2 + 2, sy / 2 - 2);
    const V2 p = side < 2 ? V2(along, (side ? 1 : -1) * (sy / 2 - off))
                          : V2((side == 2 ? 1 : -1) * (sx / 2 - off), along);
    const double yaw = (side < 2 ? 0 : 90) + w.uni(-15, 15);
    const std::string m =
        w.material(0.3, 0.7, {"noise", "checker", "stripes", "posters"}, 0.2, 0.5);
    if (w.isFree(p, 0.5 * std::hypot(lx, ly))) w.box(p.x(), p.y(), lx, ly, lz, yaw, m);
  }
  for (int k = w.uniInt(2, 5); k > 0; k--) {
    V2 p;
    const std::string m = w.material(0.3, 0.7, {"noise", "checker"}, 0.2, 0.4);
    if (!w.freeSpot(-sx / 2 + 2, -sy / 2 + 2, sx / 2 - 2, sy / 2 - 2, 1.0, p)) continue;
    const double bx = w.uni(0.6, 1.5), by = w.uni(0.6, 1.5), bz = w.uni(0.5, 1.2);
    w.box(p.x(), p.y(), bx, by, bz, w.uni(0, 90), m);
  }
  for (int k = w.count(w.spec().bushes, 0, 3); k > 0; k--) {  // potted plants
    V2 p;
    if (!w.freeSpot(-sx / 2 + 1.5, -sy / 2 + 1.5, sx / 2 - 1.5, sy / 2 - 1.5, 0.7, p)) continue;
    const double bx = w.uni(0.6, 1.1), by = w.uni(0.6, 1.1);
    w.bush(p.x(), p.y(), bx, by, w.uni(0.8, 1.6), 0, false);
  }
  // People: wandering (some pausing), standing still, standing then walking.
  const int people = w.count(w.spec().pedestrians, std::max(6, static_cast<int>(sx * sy / 60)),
                             std::max(8, static_cast<int>(sx * sy / 35)));
  const Eigen::Vector4d region(-sx / 2 + 1.5, -sy / 2 + 1.5, sx / 2 - 1.5, sy / 2 - 1.5);
  for (int k = 0; k < people; k++) {
    V2 p;
    if (w.chance(w.spec().standing) &&
        w.freeSpot(region[0], region[1], region[2], region[3], 0.6, p))
      w.stander(p);
    else
      w.walker(region, 0.6, 1.5, 3.0, w.chance(0.2) ? w.uni(3, 0.5 * w.duration()) : 0.0);
  }
}

void buildWarehouse(WorldBuilder& w) {
  const V2 size = w.size(30, 50, 22, 36);
  const double sx = size.x(), sy = size.y(), h = w.uni(6, 10);
  const double floor_albedo = w.uni(0.18, 0.28), floor_scale = w.uni(1.5, 2.5);
  w.floor(sx + 4, sy + 4, floor_albedo, "markings", floor_scale);
  walls(w, sx, sy, h);
  const double cross = w.uni(5, 7);  // cross aisles at both ends [m]
  const double side = w.uni(3.5, 4.5);
  const double depth = w.uni(1.0, 1.4), aisle = w.uni(2.6, 3.6);
  const double x0 = -sx / 2 + cross, x1 = sx / 2 - cross;
  // Rack rows along x: first the aisle centres, then the racks between them.
  std::vector<double> rows, aisles;
  for (double y = -sy / 2 + side + depth / 2; y + depth / 2 <= sy / 2 - side; y += depth + aisle)
    rows.push_back(y);
  for (std::size_t i = 0; i + 1 < rows.size(); i++) aisles.push_back(0.5 * (rows[i] + rows[i + 1]));
  if (aisles.empty()) aisles.push_back(0.0);
  // Platform: a loop through the end cross aisles, one side aisle and a middle aisle.
  const double xc = sx / 2 - cross / 2, ys = sy / 2 - side / 2;
  const double ya = aisles[aisles.size() / 2], sgn = w.chance(0.5) ? 1 : -1;
  const std::string& route = w.spec().route;
  std::vector<V2> pts;
  if (route == "auto" || route == "loop") {
    pts = {{-xc, -sgn * ys}, {xc, -sgn * ys}, {xc, ya}, {-xc, ya}};
    w.platform(pts, w.platformSpeed(1.0), true);
    w.keepOut(pts, 1.0, true);
  } else if (route == "stationary") {
    pts = {{-xc, ya}};
    w.platformStationary(pts[0], 0);
    w.keepOut(pts, 1.5, false);
  } else {
    throw std::invalid_argument("route '" + route + "' (this kind offers: loop, stationary)");
  }
  for (double y : rows) {  // bays of goods 2.7 m long, uneven heights, posts between them
    const double rh = w.uni(2.5, std::min(5.0, h - 1));
    const std::string goods =
        w.material(0.25, 0.6, {"noise", "checker", "stripes", "posters"}, 0.3, 0.8);
    for (double x = x0; x + 2.7 <= x1 + 1e-9; x += 2.78) {
      if (w.chance(0.08)) continue;  // an empty bay: see through to the next aisle
      w.box(x + 1.35, y, 2.7, depth, rh * w.uni(0.6, 1.0), 0, goods);
    }
  }
  for (int k = w.uniInt(3, 8); k > 0; k--) {  // pallets along the end walls
    const double east = w.chance(0.5) ? 1 : -1;
    const double x = east * (sx / 2 - w.uni(0.8, 1.5));
    const double y = w.uni(-sy / 2 + 1.5, sy / 2 - 1.5), height = w.uni(0.3, 1.6);
    const std::string m = w.material(0.3, 0.6, {"noise", "stripes"}, 0.2, 0.4);
    if (w.isFree({x, y}, 0.8)) w.box(x, y, 1.2, 1.0, height, 0, m);
  }
  // Workers: walking up and down aisles (pausing to pick; the platform's aisle more often),
  // wandering the cross and side aisles the platform drives through, standing.
  const int people = w.count(w.spec().pedestrians, 10, 18);
  for (int k = 0; k < people; k++) {
    const int pick = w.uniInt(0, static_cast<int>(aisles.size()) - 1);
    const double ay = w.chance(0.3) ? ya : aisles[static_cast<std::size_t>(pick)];
    const int mode = w.uniInt(0, 9);
    if (mode < 4) {
      const std::vector<V2> walk{{w.uni(x0, 0), ay}, {w.uni(0, x1), ay}};
      const double speed = w.uni(0.7, 1.4), start = w.uni(0, 8);
      w.mover("pedestrian", walk, speed, true, start, w.uni(0, 4));
    } else if (mode < 7) {
      const double cx = (w.chance(0.5) ? 1 : -1) * xc;
      w.walker({cx - cross / 2 + 1, -sy / 2 + 1.5, cx + cross / 2 - 1, sy / 2 - 1.5}, 0.7, 1.4, 3);
    } else if (mode < 9) {
      const double cy = (w.chance(0.5) ? 1 : -1) * ys;
      w.walker({x0, cy - side / 2 + 0.8, x1, cy + side / 2 - 0.8}, 0.7, 1.4, 3);
    } else {
      w.stander({w.uni(x0, x1), ay});
    }
  }
  // Forklift-sized vehicles along the aisles (never into the platform, each other or someone
  // standing: see mover()).
  for (int k = w.count(w.spec().cars, 1, 2); k > 0; k--)
    for (int tries = 0; tries < 10; tries++) {
      const int pick = w.uniInt(0, static_cast<int>(aisles.size()) - 1);
      const double ay = aisles[static_cast<std::size_t>(pick)], dir = w.chance(0.5) ? 1 : -1;
      const double speed = w.uni(1.5, 3.0), start = w.uni(0, 10), pause = w.uni(1, 5);
      if (w.mover("car", {{dir * (x0 + 2.5), ay}, {-dir * (x0 + 2.5), ay}}, speed, true, start,
                  pause))
        break;
    }
}

}  // namespace dynobj::sim::detail
