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
#include <string>
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

/// A spinning LiDAR's firing pattern, for clouds stored in the order the lasers fired (the raw
/// packet order, no ring field): each firing cycle fires every laser once, in `order`, in groups of
/// `group` lasers at the same instant; the azimuth advances 360/firings degrees per cycle.
struct FiringPattern {
  std::string name;
  std::vector<double> elevation_deg;       ///< per laser id
  std::vector<double> azimuth_offset_deg;  ///< per laser id (0 when empty)
  std::vector<double> vertical_offset_m;   ///< per laser id (0 when empty)
  std::vector<int> order;                  ///< laser ids in firing order (ids ascending when empty)
  int firings = 1800;                      ///< cycles per revolution
};

/// VLP-16: 16 lasers, 2-degree steps fired in interleaved order (-15, 1, -13, 3, ...).
inline FiringPattern vlp16Pattern() {
  FiringPattern p{"VLP-16", {}, {}, {}, {}, 1800};
  for (int i = 0; i < 16; i++) p.elevation_deg.push_back(i % 2 == 0 ? -15 + i : 1 + (i - 1));
  return p;
}

/// HDL-32E: 32 lasers 4/3 degrees apart from -30.67 to +10.67, interleaved lower/upper half.
inline FiringPattern hdl32Pattern() {
  FiringPattern p{"HDL-32E", {}, {}, {}, {}, 2170};
  for (int i = 0; i < 32; i++)
    p.elevation_deg.push_back(i % 2 == 0 ? -30.67 + 1.3333 * (i / 2) : -9.33 + 1.3333 * (i / 2));
  return p;
}

/// HDL-64E-like: an upper block (+2 to -8.3 degrees, 1/3 apart) and a lower block (-8.8 to -24.8,
/// 1/2 apart), fired in pairs (one of each block at once); each laser with its own azimuth
/// correction (up to +-5 degrees) and vertical offset (0.10-0.25 m), as in a unit's calibration.
inline FiringPattern hdl64Pattern() {
  FiringPattern p{"HDL-64E", {}, {}, {}, {}, 2048};
  std::mt19937 rng(64);
  std::uniform_real_distribution<double> az(-5.0, 5.0), v(0.10, 0.25), jitter(-0.05, 0.05);
  for (int i = 0; i < 64; i++) {
    const int k = i / 2;
    p.elevation_deg.push_back(i % 2 == 0 ? 2.0 - k / 3.0 + jitter(rng)
                                         : -8.8 - 0.5 * k + jitter(rng));
    p.azimuth_offset_deg.push_back(az(rng));
    p.vertical_offset_m.push_back(v(rng));
  }
  return p;
}

/// VLS-128-like: 128 lasers from +15 to -25 degrees, 0.11 degrees apart near the horizon, fired in
/// 16 groups of 8 simultaneous lasers spread over the elevations, azimuth offsets -6.4..+6.4
/// degrees within a group (1.8 apart), vertical offsets of a few centimetres.
inline FiringPattern vls128Pattern() {
  FiringPattern p{"VLS-128", {}, {}, {}, {}, 1800};
  std::mt19937 rng(128);
  std::uniform_real_distribution<double> v(-0.03, 0.03);
  for (int id = 0; id < 128; id++) {
    const int g = id / 8, j = id % 8;
    const int k = j * 16 + g - 64;  // elevation index -64..63: a group spans the whole fan
    const double e = 0.11 * k + (k >= 0 ? 3.2e-5 : 6.85e-5) * k * k * k;
    p.elevation_deg.push_back(e);
    p.azimuth_offset_deg.push_back(-6.3 + 1.8 * j);
    p.vertical_offset_m.push_back(v(rng));
  }
  return p;
}

/// One sweep of `p` in a street-like scene, stored in firing order: ground 1.8 m below the sensor,
/// walls 12 m high at 15-60 m depending on the azimuth (above them: sky, no return), a car-sized
/// block 5 m away at azimuths 100-130 degrees; `sweep_deg` of rotation from azimuth `start_deg`
/// (over 360: the first sector scanned twice); 2 % random no-returns, 1 cm range noise (seeded).
/// `laser` receives each point's laser id, `turn` (optional) its rotation since the sweep's start
/// [deg].
inline PointCloud rawFiringSweep(const FiringPattern& p, std::vector<int>& laser,
                                 double sweep_deg = 360.0, double start_deg = 30.0,
                                 unsigned seed = 1, std::vector<double>* turn = nullptr) {
  const int lasers = static_cast<int>(p.elevation_deg.size());
  std::vector<int> order = p.order;
  if (order.empty()) {
    order.resize(static_cast<std::size_t>(lasers));
    std::iota(order.begin(), order.end(), 0);
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> noise(0.0, 0.01);
  PointCloud c;
  laser.clear();
  if (turn) turn->clear();
  const int cycles = static_cast<int>(std::lround(p.firings * sweep_deg / 360.0));
  for (int f = 0; f < cycles; f++) {
    for (int id : order) {
      const auto l = static_cast<std::size_t>(id);
      const double rot = 360.0 * f / p.firings;
      const double az_off = p.azimuth_offset_deg.empty() ? 0.0 : p.azimuth_offset_deg[l];
      const double v = p.vertical_offset_m.empty() ? 0.0 : p.vertical_offset_m[l];
      const double az = (start_deg + rot + az_off) * kDeg, el = p.elevation_deg[l] * kDeg;
      if (u(rng) < 0.02) continue;
      double deg = std::fmod(start_deg + rot + az_off + 720.0, 360.0);
      const double wall = 15.0 + 45.0 * (0.5 + 0.5 * std::sin(3 * deg * kDeg));
      const double dz = std::sin(el), dh = std::cos(el);
      double t = 1e9;
      if (dz < 0) t = (-1.8 - v) / dz;  // the ground
      if (dh * t > wall) {              // the wall first
        t = wall / dh;
        if (v + t * dz > 10.2) t = 1e9;  // over the wall: sky
      }
      if (deg > 100 && deg < 130 && dh * t > 5.0 && v + (5.0 / dh) * dz < -0.3) t = 5.0 / dh;
      if (t > 150) continue;
      t += noise(rng);
      c.push_back(static_cast<float>(t * dh * std::cos(az)),
                  static_cast<float>(t * dh * std::sin(az)), static_cast<float>(v + t * dz),
                  static_cast<float>(id));
      laser.push_back(id);
      if (turn) turn->push_back(rot);
    }
  }
  return c;
}

}  // namespace dynobj::test
