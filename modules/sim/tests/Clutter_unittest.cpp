// SPDX-License-Identifier: BSD-3-Clause
// Porous foliage and fences: the shapes (exact hit probabilities, bars vs gaps) and the
// simulator's use of them (random subsets per sweep, never dynamic).
#include <dynobj/sim/LidarSimulator.h>
#include <gtest/gtest.h>

#include <cmath>

#include "SimTestUtil.h"

using namespace dynobj::sim;
using namespace dynobj::sim::test;

namespace {

Ray along(Eigen::Vector3d o, Eigen::Vector3d d) {
  return {o, d.normalized()};
}

/// Share of `n` keyed rays that hit, and the mean hit distance.
std::pair<double, double> hitRate(const Porous& v, const Ray& ray, double t_max, int n = 40000) {
  int hits = 0;
  double sum_t = 0;
  for (int k = 0; k < n; k++) {
    Hit h;
    if (intersect(v, ray, t_max, static_cast<std::uint64_t>(k) * 7919u + 11u, h)) {
      hits++;
      sum_t += h.t;
    }
  }
  return {static_cast<double>(hits) / n, hits ? sum_t / hits : 0.0};
}

}  // namespace

TEST(Clutter, PorousCrownHitsWithTheSetProbability) {
  // A crown of radius 1 m at 5 m, density 0.5 /m: a ray through its centre crosses 2 m of it and
  // returns with probability 1 - e^-1; the depth of the returns is exponential, truncated at 2 m
  // (mean 1/0.5 - 2 e^-1 / (1 - e^-1) = 0.836 m past the entry).
  Porous crown;
  crown.center = {5, 0, 0};
  crown.half = {1, 1, 1};
  crown.density = 0.5;
  const auto [p, mean_t] = hitRate(crown, along({0, 0, 0}, {1, 0, 0}), 100);
  EXPECT_NEAR(p, 1 - std::exp(-1.0), 0.01);  // 4 sigma over 40000 rays
  EXPECT_NEAR(mean_t, 4 + 2 - 2 * std::exp(-1.0) / (1 - std::exp(-1.0)), 0.02);
  // Off centre by 0.5 m: the chord is 2 sqrt(0.75) m. A box (hedge) of the same half sizes: 2 m.
  EXPECT_NEAR(hitRate(crown, along({0, 0.5, 0}, {1, 0, 0}), 100).first,
              1 - std::exp(-0.5 * 2 * std::sqrt(0.75)), 0.01);
  Porous hedge = crown;
  hedge.ellipsoid = false;
  EXPECT_NEAR(hitRate(hedge, along({0, 0.5, 0}, {1, 0, 0}), 100).first, 1 - std::exp(-1.0), 0.01);
  // Something nearer (t_max = 5: the first metre only) and a ray that misses.
  EXPECT_NEAR(hitRate(crown, along({0, 0, 0}, {1, 0, 0}), 5.0).first, 1 - std::exp(-0.5), 0.01);
  EXPECT_EQ(hitRate(crown, along({0, 1.01, 0}, {1, 0, 0}), 100).first, 0.0);
  // The same key always gives the same answer.
  Hit a, b;
  for (std::uint64_t key = 0; key < 50; key++) {
    const bool ha = intersect(crown, along({0, 0, 0}, {1, 0, 0}), 100, key, a);
    EXPECT_EQ(ha, intersect(crown, along({0, 0, 0}, {1, 0, 0}), 100, key, b));
    if (ha) {
      EXPECT_EQ(a.t, b.t);
      EXPECT_GE(a.t, 4.0);
      EXPECT_LE(a.t, 6.0);
      EXPECT_LE(a.normal.dot(Eigen::Vector3d(1, 0, 0)), 0.0);  // the leaf faces the sensor
    }
  }
}

TEST(Clutter, FenceBarHitGapPasses) {
  // Panel on x = 5 from y = -2 to 2, bars 4 cm wide every 0.5 m (one at each end: y = -2, ...,
  // 2), one rail at 1.0 m (5 cm), 1.2 m high.
  Fence f;
  f.a = {5, -2};
  f.b = {5, 2};
  f.z1 = 1.2;
  f.bar_width = 0.04;
  f.bar_spacing = 0.5;
  f.rail_width = 0.05;
  f.rails[0] = 1.0;
  f.rail_count = 1;
  Hit h;
  ASSERT_TRUE(intersect(f, along({0, 0, 0.5}, {1, 0, 0}), 100, h));  // bar at y = 0
  EXPECT_NEAR(h.t, 5.0, 1e-12);
  EXPECT_NEAR(h.normal.x(), -1.0, 1e-12);
  EXPECT_TRUE(intersect(f, along({0, 0.019, 0.5}, {1, 0, 0}), 100, h));   // bar edge
  EXPECT_FALSE(intersect(f, along({0, 0.021, 0.5}, {1, 0, 0}), 100, h));  // just past it
  EXPECT_FALSE(intersect(f, along({0, 0.25, 0.5}, {1, 0, 0}), 100, h));   // gap
  EXPECT_TRUE(intersect(f, along({0, 0.25, 1.02}, {1, 0, 0}), 100, h));   // rail
  EXPECT_FALSE(intersect(f, along({0, 0.25, 1.1}, {1, 0, 0}), 100, h));   // above the rail
  EXPECT_FALSE(intersect(f, along({0, 0, 1.25}, {1, 0, 0}), 100, h));     // above the fence
  EXPECT_FALSE(intersect(f, along({0, 2.5, 0.5}, {1, 0, 0}), 100, h));    // beyond its end
  EXPECT_FALSE(intersect(f, along({0, 0, 0.5}, {1, 0, 0}), 4.9, h));      // something nearer
  ASSERT_TRUE(intersect(f, along({10, 0, 0.5}, {-1, 0, 0}), 100, h));     // from behind
  EXPECT_NEAR(h.normal.x(), 1.0, 1e-12);
  // Slanted: through (5, 0.5) from the origin, a bar; through (5, 0.75), a gap.
  EXPECT_TRUE(intersect(f, along({0, 0, 0.5}, {5, 0.5, 0}), 100, h));
  EXPECT_NEAR(h.t, std::hypot(5.0, 0.5), 1e-9);
  EXPECT_FALSE(intersect(f, along({0, 0, 0.5}, {5, 0.75, 0}), 100, h));
  // Wire mesh: wires both ways every 5 cm.
  f.bar_spacing = 0.05;
  f.bar_width = 0.004;
  f.rail_spacing = 0.05;
  f.rail_width = 0.004;
  f.rail_count = 0;
  EXPECT_TRUE(intersect(f, along({0, 0.025, 0.6}, {1, 0, 0}), 100, h));     // horizontal wire
  EXPECT_FALSE(intersect(f, along({0, 0.025, 0.625}, {1, 0, 0}), 100, h));  // mesh hole
}

TEST(Clutter, SimulatedHedgeReturnsRandomSubsetsAtTheSetRate) {
  // A hedge (porous box) 2 m deep from x = 4 to 6, 40 m wide, 4 m high, density 0.3 /m, bright
  // leaves so that no return is too weak. For the rows at or above -2 deg (nothing else in
  // reach below 7 m) and columns within 60 deg of +X, each ray crosses
  // L = 2 / (cos el cos az) metres of it: the returns must total sum(1 - exp(-0.3 L)).
  const LidarSimulator sim(load(base(
      "static:\n  - {bush: {center: [5, 0], size: [2, 40, 4], shape: box, density: 0.3, sway: 0},"
      " material: {albedo: 1.0, contrast: 0}}\n")));
  const auto elev = sim.scenario().sensor.rowElevations();
  double expected = 0, observed = 0;
  cv::Mat_<std::uint8_t> first;
  for (int k = 0; k < 40; k++) {
    const auto sw = sim.simulate(k);
    for (int r = 0; r < 5; r++)
      for (int c = 0; c < 64; c++) {
        const double az = -M_PI + (c + 0.5) * 2 * M_PI / 64, el = elev[static_cast<std::size_t>(r)];
        if (std::abs(az) > 60 * kDeg) continue;
        expected += 1 - std::exp(-0.3 * 2 / (std::cos(el) * std::cos(az)));
        if (sw.frame.isValid(r, c) && sw.frame.range(r, c) < 7 / std::cos(az)) {
          observed += 1;
          EXPECT_EQ(sw.actor(r, c), -1);
          EXPECT_EQ(sw.dynamic(r, c), 0);  // foliage is static, never labelled dynamic
        }
      }
    if (k == 0) first = sw.frame.valid.clone();
    if (k == 1) {
      EXPECT_GT(cv::norm(first, sw.frame.valid, cv::NORM_L1), 0.0);  // another subset
    }
  }
  EXPECT_NEAR(observed / expected, 1.0, 0.06);
  const auto again = sim.simulate(0);  // ... but the same one for the same sweep
  EXPECT_EQ(cv::norm(first, again.frame.valid, cv::NORM_L1), 0.0);
}

TEST(Clutter, SimulatedFenceShowsBarsAndTheWallThroughTheGaps) {
  // Bars 0.5 m wide every metre on x = 5 (from y = -10), no rails, 1.5 m high; a wall at x = 10.
  // Row 3 (+2 deg) crosses the fence plane below its top for |az| < 55 deg.
  const LidarSimulator sim(load(base(
      "static:\n  - {fence: {from: [5, -10], to: [5, 10], height: 1.5, bar_width: 0.5,"
      " bar_spacing: 1.0, rails: []}}\n  - {box: {center: [10, 0, 2], size: [0.2, 40, 4]}}\n")));
  const auto sw = sim.simulate(0);
  const double el = sim.scenario().sensor.rowElevations()[3];
  int bars = 0, gaps = 0;
  for (int c = 0; c < 64; c++) {
    const double az = -M_PI + (c + 0.5) * 2 * M_PI / 64;
    if (std::abs(az) > 55 * kDeg) continue;
    const double along = 5 * std::tan(az) + 10, k = std::round(along);
    const bool bar = std::abs(along - k) <= 0.25;
    const double expected = (bar ? 5 : 9.9) / (std::cos(az) * std::cos(el));
    ASSERT_TRUE(sw.frame.isValid(3, c)) << c;
    EXPECT_NEAR(sw.frame.range(3, c), expected, 1e-4) << c;
    (bar ? bars : gaps)++;
  }
  EXPECT_GT(bars, 2);
  EXPECT_GT(gaps, 2);
}
