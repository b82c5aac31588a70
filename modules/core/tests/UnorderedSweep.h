// SPDX-License-Identifier: BSD-3-Clause
// Test helper: a hand-made unordered sweep whose true beam of every point is known (an uneven
// 6-beam table, like a real unit's), stored in firing order or shuffled; the tests of row recovery
// and of core::SweepProjector read it.
#pragma once

#include <dynobj/core/PointCloud.h>
#include <dynobj/core/SensorModel.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

namespace dynobj::test {

using core::PointCloud;
using core::SensorModel;

constexpr double kDeg = M_PI / 180.0;
/// Beam elevations [deg] top-down, unevenly spaced.
inline const std::vector<double> kBeams = {4.1, 2.0, 1.2, -3.5, -4.0, -9.0};
constexpr int kFirings = 360;

/// One sweep stored laser by laser (top beam first), each laser one revolution starting at
/// azimuth `start`; every 7th firing of each laser is a no-return. `laser` receives each point's
/// beam (index into kBeams). Ranges 20-40 m.
inline PointCloud firingOrderSweep(std::vector<int>& laser, double start = 10 * kDeg,
                                   int lasers = static_cast<int>(kBeams.size())) {
  PointCloud c;
  laser.clear();
  for (int l = 0; l < lasers; l++)
    for (int k = 0; k < kFirings; k++) {
      if ((k + l) % 7 == 0) continue;
      const double az = start + 2 * M_PI * k / kFirings, el = kBeams[l] * kDeg;
      const double r = 20.0 + 20.0 * ((k * 37 + l * 11) % 100) / 100.0;
      c.push_back(static_cast<float>(r * std::cos(el) * std::cos(az)),
                  static_cast<float>(r * std::cos(el) * std::sin(az)),
                  static_cast<float>(r * std::sin(el)), static_cast<float>(l));
      laser.push_back(l);
    }
  return c;
}

inline SensorModel hint(int cols = kFirings) {
  SensorModel s;
  s.model = "six";
  s.rows = static_cast<int>(kBeams.size());
  s.cols = cols;
  s.elevation_top = 5 * kDeg;  // a nominal, evenly spaced table: wrong for this unit
  s.elevation_bottom = -10 * kDeg;
  return s;
}

/// Shuffles the points of `c` (and `laser` with them), with a fixed seed.
inline void shuffle(PointCloud& c, std::vector<int>& laser) {
  std::vector<std::size_t> order(c.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  PointCloud out;
  std::vector<int> l;
  for (std::size_t i : order) {
    out.push_back(c.x[i], c.y[i], c.z[i], c.intensity[i]);
    if (!c.ring.empty()) out.ring.push_back(c.ring[i]);
    l.push_back(laser[i]);
  }
  c = out;
  laser = l;
}

}  // namespace dynobj::test
