// SPDX-License-Identifier: BSD-3-Clause
// Parking lot layout: rows of slots (single along the edges, back to back inside) between
// driving lanes, parked cars, some of which pull out during the sequence and drive away, cars
// cruising the lanes, people walking between the cars, islands with trees and bushes, lamp posts,
// a perimeter fence with gaps at the lanes, a shop front beyond it.
#include <cmath>
#include <stdexcept>

#include "WorldBuilder.h"

namespace dynobj::sim::detail {
namespace {

using V2 = Eigen::Vector2d;

struct Slot {
  V2 at;
  double lane_y;  ///< the lane its nose points to
  bool nose_out;  ///< parked facing the lane: can pull out forwards
};

}  // namespace

void buildParking(WorldBuilder& w) {
  const V2 size = w.size(40, 70, 30, 50);
  const double sx = size.x(), sy = size.y();
  constexpr double kSlotW = 2.6, kSlotD = 5.0, kLane = 6.5, kEnd = 6.0;
  const double floor_albedo = w.uni(0.12, 0.22);
  w.floor(sx + 60, sy + 60, floor_albedo, "markings", w.uni(2.4, 2.8));
  // Rows and lanes from the bottom edge up.
  std::vector<double> lanes;
  std::vector<std::pair<double, double>> rows;  // (centre y, direction of its lane: +1 / -1)
  double y = -sy / 2 + 0.5;
  rows.push_back({y + kSlotD / 2, 1});
  y += kSlotD;
  while (true) {
    lanes.push_back(y + kLane / 2);
    y += kLane;
    if (y + 2 * kSlotD + kLane + kSlotD <= sy / 2 - 0.5) {
      rows.push_back({y + kSlotD / 2, -1});
      rows.push_back({y + 1.5 * kSlotD, 1});
      y += 2 * kSlotD;
    } else {
      rows.push_back({y + kSlotD / 2, -1});
      break;
    }
  }
  const double top = y + kSlotD;  // the lot's upper edge
  const double x0 = -sx / 2 + kEnd, x1 = sx / 2 - kEnd, xe = sx / 2 - kEnd / 2;
  constexpr double kKeep = 1.6;  // [m] vehicles keep this far right of a lane's centre line
  // Platform: around the lanes (or standing at the end of one).
  const std::string& route = w.spec().route;
  std::vector<V2> pts;
  if (route == "auto" || route == "loop") {
    // Out along the first lane and back along the last (or the same one), keeping right.
    const double k = w.chance(0.5) ? kKeep : -kKeep;  // which way round
    pts = {{-xe, lanes.front() - k},
           {xe, lanes.front() - k},
           {xe, lanes.back() + k},
           {-xe, lanes.back() + k}};
    if (k < 0) std::reverse(pts.begin(), pts.end());
    w.platform(pts, w.platformSpeed(3.0), true, 2.0);  // a car: 2 m kept clear of others
    w.keepOut(pts, 1.5, true);
  } else if (route == "stationary") {
    pts = {{-xe, lanes.front() - kKeep}};
    w.platformStationary(pts[0], 0, 2.0);
    w.keepOut(pts, 1.5, false);
  } else {
    throw std::invalid_argument("route '" + route + "' (this kind offers: loop, stationary)");
  }
  // Slots: parked cars, some of them leaving. The first and last slot of a row is an island.
  const double occupancy = w.spec().occupancy >= 0 ? w.spec().occupancy : w.uni(0.55, 0.85);
  std::vector<Slot> taken;
  for (const auto& [ry, dir] : rows)
    for (double x = x0 + 1.5 * kSlotW; x <= x1 - 1.5 * kSlotW + 1e-9; x += kSlotW)
      if (w.chance(occupancy))
        taken.push_back(
            {{x + w.uni(-0.15, 0.15), ry}, ry + dir * (kSlotD / 2 + kLane / 2), w.chance(0.7)});
  int leaving = w.count(w.spec().pulling_out, 2, 5);
  std::vector<bool> leaves(taken.size(), false);
  for (int tries = 0; leaving > 0 && tries < 200 && !taken.empty(); tries++) {
    const auto k = static_cast<std::size_t>(w.uniInt(0, static_cast<int>(taken.size()) - 1));
    if (leaves[k] || !taken[k].nose_out) continue;
    leaves[k] = true;
    leaving--;
  }
  for (std::size_t k = 0; k < taken.size(); k++) {
    const Slot& s = taken[k];
    const double yaw = (s.lane_y > s.at.y()) == s.nose_out ? 90 : -90;
    if (!leaves[k]) {
      w.parkedCar(s.at.x(), s.at.y(), yaw + w.uni(-4, 4));
      continue;
    }
    const double exit = (w.chance(0.5) ? 1 : -1) * (sx / 2 + 15);
    const double yl = s.lane_y + (exit > 0 ? -kKeep : kKeep);  // keeping right
    const double speed = w.uni(2, 4), start = w.uni(1, 0.75 * w.duration());
    if (w.mover("car", {s.at, {s.at.x(), yl}, {exit, yl}}, speed, false, start))
      w.keepOutDisc(s.at, 2.3);
    else  // it would drive into the platform, another vehicle or someone standing: it stays
      w.parkedCar(s.at.x(), s.at.y(), yaw);
  }
  // Islands at the row ends: trees, bushes, lamp posts.
  int trees = w.count(w.spec().trees, 4, 10), bushes = w.count(w.spec().bushes, 3, 8);
  for (const auto& [ry, dir] : rows)
    for (double side : {-1.0, 1.0}) {
      const V2 p(side * (sx / 2 - kEnd - kSlotW / 2), ry);
      if (!w.isFree(p, 0.9)) continue;
      if (trees > 0 && w.chance(0.5)) {
        const double height = w.uni(5, 9);
        w.tree(p.x(), p.y(), height, w.uni(1.5, 3.0));
        trees--;
      } else if (bushes > 0 && w.chance(0.6)) {
        const double bx = w.uni(1.0, 1.8), by = w.uni(2, 4.5), bz = w.uni(0.6, 1.3);
        w.bush(p.x(), p.y(), bx, by, bz, 0, w.chance(0.5));
        bushes--;
      } else {
        w.cylinder(p.x(), p.y(), 0.12, w.uni(7, 10),
                   "{albedo: 0.55, pattern: stripes, scale: 0.4}");
      }
    }
  // Perimeter: fences along the long sides, gaps where the lanes leave; trees outside.
  const std::string style = w.chance(0.5) ? "mesh" : "bars";
  const double fh = w.uni(1.2, 2.0);
  if (w.count(w.spec().fences, 1, 1) > 0) {
    w.fence({-sx / 2, -sy / 2 - 0.3}, {sx / 2, -sy / 2 - 0.3}, fh, style);
    w.fence({-sx / 2, top + 0.3}, {sx / 2, top + 0.3}, fh, style);
    for (double side : {-1.0, 1.0}) {
      double from = -sy / 2 - 0.3;
      for (double lane : lanes) {
        if (lane - kLane / 2 - from > 0.5)
          w.fence({side * sx / 2, from}, {side * sx / 2, lane - kLane / 2}, fh, style);
        from = lane + kLane / 2;
      }
      if (top + 0.3 - from > 0.5)
        w.fence({side * sx / 2, from}, {side * sx / 2, top + 0.3}, fh, style);
    }
  }
  for (; trees > 0; trees--) {
    const V2 p{w.uni(-sx / 2, sx / 2), w.chance(0.5) ? -sy / 2 - 3 : top + 3};
    if (w.isFree(p, 1.0)) {
      const double height = w.uni(6, 11);
      w.tree(p.x(), p.y(), height, w.uni(2, 3.5));
    }
  }
  const double shop_x = w.uni(-sx / 6, sx / 6), shop_len = sx * w.uni(0.5, 0.8);
  const double shop_h = w.uni(6, 10);
  w.box(shop_x, top + 12, shop_len, 12, shop_h, 0,
        w.material(0.35, 0.6, {"posters", "checker", "noise"}, 1.5, 2.5));
  // Cars cruising the lanes, people walking between the cars.
  for (int k = w.count(w.spec().cars, 1, 3); k > 0; k--)
    for (int tries = 0; tries < 10; tries++) {  // not into the platform or others (mover())
      const double la =
          lanes[static_cast<std::size_t>(w.uniInt(0, static_cast<int>(lanes.size()) - 1))];
      const double lb =
          lanes[static_cast<std::size_t>(w.uniInt(0, static_cast<int>(lanes.size()) - 1))];
      const double xc = xe - kKeep, speed = w.uni(2.5, 4.5);
      const std::vector<V2> loop{
          {xc, la + kKeep}, {-xc, la + kKeep}, {-xc, lb - kKeep}, {xc, lb - kKeep}};
      if (w.mover("car", WorldBuilder::loopFrom(loop, w.uni(0, 1)), speed, true, 0)) break;
    }
  const int people = w.count(w.spec().pedestrians, 4, 12);
  for (int k = 0; k < people; k++) {
    const double la =
        lanes[static_cast<std::size_t>(w.uniInt(0, static_cast<int>(lanes.size()) - 1))];
    V2 p;
    if (w.chance(w.spec().standing) && w.freeSpot(x0, la - 2.5, x1, la + 2.5, 0.6, p))
      w.stander(p);
    else
      w.walker({x0, la - 2.8, x1, la + 2.8}, 0.8, 1.5, 3.0,
               w.chance(0.3) ? w.uni(2, 0.5 * w.duration()) : 0.0);
  }
}

}  // namespace dynobj::sim::detail
