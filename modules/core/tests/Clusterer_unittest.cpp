// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Clusterer.h>
#include <gtest/gtest.h>

#include <random>

#include "SyntheticScene.h"

using namespace dynobj::core;

namespace {

/// Features = every valid pixel of a frame built from explicit points (row, col, x, y, z).
LidarFrame pointsFrame(const std::vector<std::array<float, 5>>& pts) {
  LidarFrame f(dynobj::test::smallSensor(16, 64));
  int i = 0;
  for (const auto& p : pts)
    f.setPixel(static_cast<int>(p[0]), static_cast<int>(p[1]), std::hypot(p[2], p[3], p[4]), 1.f,
               cv::Vec3f(p[2], p[3], p[4]), i++);
  return f;
}

}  // namespace

TEST(Clusterer, TwoGroupsOneMetreApartGiveTwoClusters) {
  // Group A around (5, 0, 0), group B around (5, 1, 0): 1 m apart, each 3 points 0.1 m apart.
  const LidarFrame f = pointsFrame({{8, 10, 5, 0, 0},
                                    {8, 11, 5, 0.1f, 0},
                                    {9, 10, 5, 0, -0.1f},
                                    {8, 20, 5, 1.0f, 0},
                                    {8, 21, 5, 1.1f, 0},
                                    {9, 20, 5, 1.0f, -0.1f}});
  cv::Mat_<std::uint8_t> features = f.valid.clone();
  for (bool kd : {true, false}) {
    ClusteringParams p;
    p.kdtree = kd;
    p.min_points = 2;
    std::vector<Cluster> out;
    Clusterer(p).cluster(f, features, out);
    ASSERT_EQ(out.size(), 2u) << (kd ? "kdtree" : "image");
    EXPECT_EQ(out[0].pixels.size(), 3u);
    EXPECT_NEAR(std::min(out[0].centroid.y(), out[1].centroid.y()), 0.1 / 3, 1e-5);
    EXPECT_NEAR(std::max(out[0].centroid.y(), out[1].centroid.y()), 1.0 + 0.1 / 3, 1e-5);
  }
}

TEST(Clusterer, HorizontalAndVerticalThresholdsAreSeparate) {
  // Two points 0.3 m apart horizontally (< 0.35) and two 0.5 m apart vertically (< 0.6), and one
  // 0.4 m apart horizontally (> 0.35): Eq. (6)-(7) with eps = (0.35, 0.6).
  const LidarFrame f = pointsFrame({{8, 10, 5, 0, 0}, {8, 12, 5, 0.3f, 0}, {5, 10, 5, 0, 0.5f},
                                    {8, 16, 5, 0.7f, 0}});
  ClusteringParams p;
  p.min_points = 1;
  std::vector<Cluster> out;
  Clusterer(p).cluster(f, f.valid, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].pixels.size() + out[1].pixels.size(), 4u);
  EXPECT_TRUE(out[0].pixels.size() == 3u || out[1].pixels.size() == 3u);
}

TEST(Clusterer, ImageWindowEqualsKdTreeOnASparseScene) {
  // Oracle: with objects far enough that the image window covers epsilon, both searches agree.
  dynobj::test::Scene scene;
  scene.posts = {{6, 0, 0.3, 1.7}, {6, 0.5, 0.3, 1.7}, {-5, 4, 0.25, 1.8}, {2, -7, 0.3, 1.0}};
  const LidarFrame f = dynobj::test::render(scene, dynobj::test::smallSensor(16, 360));
  cv::Mat_<std::uint8_t> features(f.rows(), f.cols(), std::uint8_t{0});
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++)
      if (f.isValid(r, c) && f.range(r, c) < 11.0f && f.xyz(r, c)[2] > -0.99f) features(r, c) = 255;
  ClusteringParams a, b;
  a.kdtree = true;
  b.kdtree = false;
  b.max_window = 64;
  a.min_points = b.min_points = 1;
  std::vector<Cluster> ca, cb;
  Clusterer(a).cluster(f, features, ca);
  Clusterer(b).cluster(f, features, cb);
  ASSERT_EQ(ca.size(), cb.size());
  auto sizes = [](const std::vector<Cluster>& v) {
    std::vector<std::size_t> s;
    for (const auto& c : v) s.push_back(c.pixels.size());
    std::sort(s.begin(), s.end());
    return s;
  };
  EXPECT_EQ(sizes(ca), sizes(cb));
  EXPECT_EQ(ca.size(), 3u);  // the two close posts merge (0.5 m apart, edges 0.2 m)
}

TEST(Clusterer, PcaOfAWall) {
  std::vector<std::array<float, 5>> pts;
  for (int i = 0; i < 20; i++) pts.push_back({8, static_cast<float>(10 + i), 5, -1.0f + 0.1f * i, 0});
  const LidarFrame f = pointsFrame(pts);
  ClusteringParams p;
  std::vector<Cluster> out;
  Clusterer(p).cluster(f, f.valid, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(std::abs(out[0].main_direction.y()), 1.0, 1e-6);  // along +Y
  EXPECT_NEAR(out[0].length, 1.9, 1e-5);
  EXPECT_GT(out[0].elongation, 10);
}
