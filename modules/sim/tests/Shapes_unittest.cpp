// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/sim/Shapes.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynobj::sim;

namespace {
Ray ray(Eigen::Vector3d o, Eigen::Vector3d d) {
  return {o, d.normalized()};
}
}  // namespace

TEST(Shapes, BoxWallAtKnownDistance) {
  const Box wall{{5.1, 0, 1}, {0.1, 10, 2}, 0.0};  // front face at x = 5
  Hit h;
  ASSERT_TRUE(intersect(wall, ray({0, 0, 1}, {1, 0, 0}), 100, h));
  EXPECT_NEAR(h.t, 5.0, 1e-12);
  EXPECT_NEAR(h.normal.x(), -1.0, 1e-12);
  ASSERT_TRUE(intersect(wall, ray({0, 0, 1}, {1, 1, 0}), 100, h));  // 45 deg: 5 * sqrt(2)
  EXPECT_NEAR(h.t, 5.0 * std::sqrt(2.0), 1e-9);
  EXPECT_FALSE(intersect(wall, ray({0, 0, 1}, {-1, 0, 0}), 100, h));   // behind
  EXPECT_FALSE(intersect(wall, ray({0, 0, 1}, {1, 0, 0}), 4.9, h));    // beyond t_max
  EXPECT_FALSE(intersect(wall, ray({5.1, 0, 1}, {1, 0, 0}), 100, h));  // starts inside
}

TEST(Shapes, YawedBox) {
  const Box b{{10, 0, 0}, {1, 1, 1}, M_PI / 4};  // a diamond seen from the origin
  Hit h;
  ASSERT_TRUE(intersect(b, ray({0, 0, 0}, {1, 0, 0}), 100, h));
  EXPECT_NEAR(h.t, 10 - std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(std::abs(h.normal.x()), std::sqrt(0.5), 1e-9);
}

TEST(Shapes, CylinderSideAndCap) {
  const Cylinder c{{5, 0}, 0.5, 0.0, 2.0};
  Hit h;
  ASSERT_TRUE(intersect(c, ray({0, 0, 1}, {1, 0, 0}), 100, h));
  EXPECT_NEAR(h.t, 4.5, 1e-12);
  EXPECT_NEAR(h.normal.x(), -1.0, 1e-12);
  ASSERT_TRUE(intersect(c, ray({5, 0, 4}, {0, 0, -1}), 100, h));  // from above: top cap
  EXPECT_NEAR(h.t, 2.0, 1e-12);
  EXPECT_NEAR(h.normal.z(), 1.0, 1e-12);
  EXPECT_FALSE(intersect(c, ray({0, 0, 3}, {1, 0, 0}), 100, h));  // passes above
  EXPECT_FALSE(intersect(c, ray({0, 1, 1}, {1, 0, 0}), 100, h));  // passes beside
}

TEST(Shapes, FloorFromAbove) {
  const Floor f{0, -10, 10, -10, 10};
  Hit h;
  ASSERT_TRUE(intersect(f, ray({0, 0, 1}, {1, 0, -1}), 100, h));
  EXPECT_NEAR(h.t, std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(h.uv.x(), 1.0, 1e-12);
  EXPECT_FALSE(intersect(f, ray({0, 0, 1}, {1, 0, 0.1}), 100, h));    // upwards
  EXPECT_FALSE(intersect(f, ray({0, 0, 1}, {100, 0, -1}), 1000, h));  // lands outside the floor
}
