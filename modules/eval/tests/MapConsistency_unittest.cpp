// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/SphericalProjection.h>
#include <dynobj/eval/MapConsistency.h>
#include <gtest/gtest.h>

#include <cmath>

using namespace dynobj;

namespace {

core::SensorModel sensor() {
  core::SensorModel s;
  s.model = "test";
  s.rows = 32;
  s.cols = 360;
  s.elevation_top = 15 * M_PI / 180;
  s.elevation_bottom = -15 * M_PI / 180;
  s.max_range = 50;
  return s;
}

/// A still sensor looking at a wall at x = 10 m (y in [-4, 4], z in [-1, 1]) and a 0.6 m box that
/// walks along y in front of it at x = 6 m, 0.2 m per sweep from y = -3.
core::LidarFrame sweep(int k, cv::Mat_<std::uint8_t>& box_mask) {
  const core::SensorModel s = sensor();
  core::PointCloud cloud;
  const double box_y = -3 + 0.2 * k;
  for (int r = 0; r < s.rows; r++)
    for (int c = 0; c < s.cols; c++) {
      const double el =
          s.elevation_top - (r + 0.5) * (s.elevation_top - s.elevation_bottom) / s.rows;
      const double az = M_PI - (c + 0.5) * 2 * M_PI / s.cols;
      const Eigen::Vector3d d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                              std::sin(el));
      if (d.x() <= 0.1) continue;
      Eigen::Vector3d p = d * (6.0 / d.x());  // the box's front face
      if (std::abs(p.y() - box_y) > 0.3 || std::abs(p.z()) > 0.5) p = d * (10.0 / d.x());
      if (std::abs(p.y()) > 4 || std::abs(p.z()) > 1) continue;
      cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                      static_cast<float>(p.z()), 1.f);
    }
  core::LidarFrame f(s);
  core::SphericalProjection(s).project(cloud, f);
  f.timestamp_ns = k;
  box_mask.create(f.rows(), f.cols());
  box_mask.setTo(0);
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++)
      if (f.valid(r, c) && f.range(r, c) < 8) box_mask(r, c) = 255;
  return f;
}

}  // namespace

TEST(MapConsistency, MoverIsTransientAndFlaggedWallIsSuspicious) {
  eval::MapConsistency truth, wall_flagged;
  long box_points = 0;
  for (int k = 0; k < 30; k++) {
    cv::Mat_<std::uint8_t> box;
    const core::LidarFrame f = sweep(k, box);
    box_points += cv::countNonZero(box);
    truth.add(f, Eigen::Isometry3d::Identity(), box);  // the box flagged: right
    cv::Mat_<std::uint8_t> wall = f.valid & ~box;      // the wall flagged: wrong
    wall_flagged.add(f, Eigen::Isometry3d::Identity(), wall);
  }
  ASSERT_GT(box_points, 100);
  const eval::ConsistencyReport good = truth.evaluate();
  EXPECT_EQ(good.sweeps, 30);
  EXPECT_EQ(good.flagged, box_points);
  EXPECT_GT(good.transientShare(), 0.7) << good.toString();  // the box edges: undecided (3x3)
  EXPECT_LT(good.suspiciousShare(), 0.05) << good.toString();
  const eval::ConsistencyReport bad = wall_flagged.evaluate();
  EXPECT_GT(bad.suspiciousShare(), 0.8) << bad.toString();
  EXPECT_GT(bad.unflagged_transient, 0) << "the unflagged box should look missed";
  const cv::Mat img = truth.topView(0.1);
  EXPECT_FALSE(img.empty());
  EXPECT_EQ(img.type(), CV_8UC3);
}
