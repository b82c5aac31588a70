// SPDX-License-Identifier: BSD-3-Clause
// PointGrid: the nearest point within one cell size, against brute force.
#include <dynobj/core/Config.h>
#include <dynobj/core/PointGrid.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

using namespace dynobj::core;

TEST(PointGrid, NearestWithinTheCellMatchesBruteForce) {
  std::mt19937 rng(27);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (double cell : {0.2, 0.5, 1.3}) {
    PointGrid grid(cell);
    std::vector<Eigen::Vector3d> pts;
    for (int i = 0; i < 400; i++) {
      pts.emplace_back(u(rng), u(rng), 0.3 * u(rng));
      grid.add(pts.back());
    }
    for (int k = 0; k < 2000; k++) {
      const Eigen::Vector3d q(u(rng), u(rng), 0.3 * u(rng));
      double best = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector3d& p : pts) {
        const double d = (p - q).squaredNorm();
        if (d <= cell * cell) best = std::min(best, d);
      }
      const double got = grid.nearestSq(q);
      if (std::isinf(best))
        EXPECT_TRUE(std::isinf(got)) << "cell " << cell << " query " << k;
      else
        EXPECT_DOUBLE_EQ(got, best) << "cell " << cell << " query " << k;
    }
  }
}

TEST(PointGrid, EmptyNegativeCellsAndBadSize) {
  PointGrid grid(0.5);
  EXPECT_TRUE(grid.empty());
  EXPECT_TRUE(std::isinf(grid.nearestSq({0, 0, 0})));
  grid.add({-2.01, -0.49, 1.0});  // negative cells
  EXPECT_FALSE(grid.empty());
  EXPECT_DOUBLE_EQ(grid.nearestSq({-2.01, -0.49, 1.2}), 0.04);
  EXPECT_TRUE(std::isinf(grid.nearestSq({-2.01, -0.49, 1.6})));  // farther than the cell
  EXPECT_THROW(PointGrid(0.0), ParameterError);
}
