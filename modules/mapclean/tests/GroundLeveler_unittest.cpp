// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/GroundLeveler.h>
#include <gtest/gtest.h>

#include <cmath>

namespace mc = dynobj::mapclean;
using dynobj::core::LidarFrame;
using dynobj::core::SensorModel;

namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Isometry3d pose(double x, double y, double z, double yaw, double pitch, double roll) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  p.translation() = Eigen::Vector3d(x, y, z);
  p.linear() = (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return p;
}

/// What a 32 x 360 sensor at `truth` sees of an endless floor at z = 0 (nothing else).
LidarFrame floorScan(const Eigen::Isometry3d& truth) {
  SensorModel s;
  s.rows = 32;
  s.cols = 360;
  s.elevation_top = 10 * kDeg;
  s.elevation_bottom = -30 * kDeg;
  LidarFrame f(s);
  const auto el = s.rowElevations();
  for (int r = 0; r < s.rows; r++)
    for (int c = 0; c < s.cols; c++) {
      const double az = -M_PI + (c + 0.5) * 2 * M_PI / s.cols;
      const Eigen::Vector3d d(std::cos(el[r]) * std::cos(az), std::cos(el[r]) * std::sin(az),
                              std::sin(el[r]));
      const double dz = (truth.linear() * d).z();
      if (dz > -1e-3) continue;
      const double t = -truth.translation().z() / dz;
      if (t > 40) continue;
      const Eigen::Vector3d p = t * d;
      f.setPixel(r, c, static_cast<float>(t), 100.f, cv::Vec3f(p.x(), p.y(), p.z()),
                 r * s.cols + c);
    }
  return f;
}

}  // namespace

TEST(GroundLeveler, RestoresRollPitchAndHeightKeepsXYAndYaw) {
  mc::GroundLeveler leveler;
  // Scan 0: the odometry says (2, 3, 0.65), yaw 30 deg, level; truly the sensor is 0.60 m above the
  // floor, pitched by 3 deg. Scan 1: truly 0.70 m high, rolled by -2 deg.
  const Eigen::Isometry3d truth0 = pose(2, 3, 0.60, 30 * kDeg, 3 * kDeg, 0);
  const auto g0 = leveler.fit(floorScan(truth0));
  ASSERT_TRUE(g0.has_value());
  EXPECT_NEAR(g0->distance, 0.60, 1e-4);
  const Eigen::Isometry3d l0 = leveler.level(pose(2, 3, 0.65, 30 * kDeg, 0, 0), *g0);
  EXPECT_TRUE(l0.linear().isApprox(truth0.linear(), 1e-5));
  EXPECT_NEAR(l0.translation().x(), 2, 1e-9);
  EXPECT_NEAR(l0.translation().y(), 3, 1e-9);
  EXPECT_NEAR(l0.translation().z(), 0.65, 1e-4);  // the first scan fixes the floor at z = 0.05

  const Eigen::Isometry3d truth1 = pose(4, 3, 0.70, -45 * kDeg, 0, -2 * kDeg);
  const auto g1 = leveler.fit(floorScan(truth1));
  ASSERT_TRUE(g1.has_value());
  const Eigen::Isometry3d l1 = leveler.level(pose(4, 3, 0.65, -45 * kDeg, 0, 0), *g1);
  EXPECT_TRUE(l1.linear().isApprox(truth1.linear(), 1e-5));
  EXPECT_NEAR(l1.translation().z(), 0.75, 1e-4);
}

TEST(GroundLeveler, NoFloorNoLevel) {
  mc::GroundLeveler leveler;
  SensorModel s;
  s.rows = 32;
  s.cols = 360;
  EXPECT_FALSE(leveler.fit(LidarFrame(s)).has_value());
}
