// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Clusterer.h>
#include <dynobj/core/Config.h>
#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <set>

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
  ClusteringParams p;
  p.min_points = 2;
  std::vector<Cluster> out;
  Clusterer(p).cluster(f, features, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].pixels.size(), 3u);
  EXPECT_NEAR(std::min(out[0].centroid.y(), out[1].centroid.y()), 0.1 / 3, 1e-5);
  EXPECT_NEAR(std::max(out[0].centroid.y(), out[1].centroid.y()), 1.0 + 0.1 / 3, 1e-5);
}

TEST(Clusterer, HorizontalAndVerticalThresholdsAreSeparate) {
  // Two points 0.3 m apart horizontally (< 0.35) and two 0.5 m apart vertically (< 0.6), and one
  // 0.4 m apart horizontally (> 0.35): Eq. (6)-(7) with eps = (0.35, 0.6).
  const LidarFrame f = pointsFrame(
      {{8, 10, 5, 0, 0}, {8, 12, 5, 0.3f, 0}, {5, 10, 5, 0, 0.5f}, {8, 16, 5, 0.7f, 0}});
  ClusteringParams p;
  p.min_points = 1;
  std::vector<Cluster> out;
  Clusterer(p).cluster(f, f.valid, out);
  ASSERT_EQ(out.size(), 2u);
  EXPECT_EQ(out[0].pixels.size() + out[1].pixels.size(), 4u);
  EXPECT_TRUE(out[0].pixels.size() == 3u || out[1].pixels.size() == 3u);
}

TEST(Clusterer, GridEqualsBruteForceOnRandomPoints) {
  // Oracle: single linkage under Eq. (6)-(7) by brute force (all pairs), on random points with
  // distances around both thresholds; every feature is its own voxel (voxel = 0).
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> xy(-2.f, 2.f), z(-1.5f, 1.5f);
  for (int trial = 0; trial < 20; trial++) {
    std::vector<std::array<float, 5>> pts;
    const int n = 50 + 30 * trial;
    for (int i = 0; i < n; i++)
      pts.push_back(
          {static_cast<float>(i / 64), static_cast<float>(i % 64), xy(rng), xy(rng), z(rng)});
    const LidarFrame f = pointsFrame(pts);
    ClusteringParams p;
    p.voxel = 0;
    p.min_points = 1;
    p.max_points = 100000;
    std::vector<int> parent(pts.size());
    for (int i = 0; i < n; i++) parent[i] = i;
    const std::function<int(int)> find = [&](int x) {
      return parent[x] == x ? x : parent[x] = find(parent[x]);
    };
    for (int i = 0; i < n; i++)
      for (int j = i + 1; j < n; j++)
        if (std::hypot(pts[i][2] - pts[j][2], pts[i][3] - pts[j][3]) <= p.horizontal_distance &&
            std::abs(pts[i][4] - pts[j][4]) <= p.vertical_distance)
          parent[find(i)] = find(j);
    std::set<std::set<int>> expected;
    std::map<int, std::set<int>> groups;
    for (int i = 0; i < n; i++)
      groups[find(i)].insert(static_cast<int>(pts[i][0]) * 64 + static_cast<int>(pts[i][1]));
    for (auto& [root, g] : groups) expected.insert(g);
    std::vector<Cluster> out;
    Clusterer(p).cluster(f, f.valid, out);
    std::set<std::set<int>> got;
    for (const Cluster& c : out) got.insert(std::set<int>(c.pixels.begin(), c.pixels.end()));
    EXPECT_EQ(got, expected) << "trial " << trial << ", " << expected.size() << " clusters";
  }
}

TEST(Clusterer, PcaOfAWall) {
  std::vector<std::array<float, 5>> pts;
  for (int i = 0; i < 20; i++)
    pts.push_back({8, static_cast<float>(10 + i), 5, -1.0f + 0.1f * i, 0});
  const LidarFrame f = pointsFrame(pts);
  ClusteringParams p;
  std::vector<Cluster> out;
  Clusterer(p).cluster(f, f.valid, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_NEAR(std::abs(out[0].main_direction.y()), 1.0, 1e-6);  // along +Y
  EXPECT_NEAR(out[0].length, 1.9, 1e-5);
  EXPECT_GT(out[0].elongation, 10);
}

TEST(Clusterer, MaxAreaCountsVoxelsNotPixels) {
  // A: 40 features packed in one 0.17 m voxel (a near object: many pixels, tiny area).
  // B: a 2 m x 1 m sheet, one feature every 0.2 m: 66 features in 66 voxels = 1.9 m^2.
  std::vector<std::array<float, 5>> pts;
  for (int i = 0; i < 40; i++)
    pts.push_back({0.f + i / 32, static_cast<float>(i % 32), 3.01f + 0.003f * (i % 7),
                   -2.01f + 0.003f * (i % 5), 0.01f});
  for (int i = 0; i < 11; i++)
    for (int j = 0; j < 6; j++)
      pts.push_back(
          {static_cast<float>(4 + j), static_cast<float>(i), 6.f + 0.2f * i, 2.f, 0.2f * j - 0.5f});
  const LidarFrame f = pointsFrame(pts);
  ClusteringParams p;
  p.min_points = 1;
  p.max_area = 1.0;  // m^2: the sheet is larger, the packed object is not
  std::vector<Cluster> out;
  Clusterer(p).cluster(f, f.valid, out);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].pixels.size(), 40u);
  std::vector<int> dropped;  // the sheet's 66 features, when asked for
  Clusterer(p).cluster(f, f.valid, out, nullptr, &dropped);
  EXPECT_EQ(out.size(), 1u);
  EXPECT_EQ(dropped.size(), 66u);
  for (int px : dropped) EXPECT_GE(px / f.cols(), 4);  // rows 4-9: the sheet's
  p.max_area = 3.0;                                    // both fit
  Clusterer(p).cluster(f, f.valid, out);
  EXPECT_EQ(out.size(), 2u);
  p.max_area = 0;  // no limit
  Clusterer(p).cluster(f, f.valid, out);
  EXPECT_EQ(out.size(), 2u);
}

// Weak clusters (beyond the paper, docs/algorithm.md §5): the components with fewer than
// min_points features but at least weak_min_points.
TEST(Clusterer, WeakClustersAreTheComponentsBetweenWeakMinPointsAndMinPoints) {
  // Components of 3, 2 and 1 points, 1 m apart; min_points 3, weak_min_points 2.
  LidarFrame f(dynobj::test::smallSensor(16, 64));
  int i = 0;
  for (const auto& p : std::vector<std::array<float, 3>>{
           {5, 0, 0}, {5, 0.1f, 0}, {5, 0.2f, 0}, {5, 1, 0}, {5, 1.1f, 0}, {5, 2, 0}})
    f.setPixel(8, 10 + 2 * i, 5, 1.f, cv::Vec3f(p[0], p[1], p[2]), i), i++;
  ClusteringParams p;
  p.min_points = 3;
  p.weak_min_points = 2;
  std::vector<Cluster> out, weak;
  Clusterer(p).cluster(f, f.valid, out, &weak);
  ASSERT_EQ(out.size(), 1u);
  EXPECT_EQ(out[0].pixels.size(), 3u);
  ASSERT_EQ(weak.size(), 1u);
  EXPECT_EQ(weak[0].pixels.size(), 2u);
  EXPECT_NEAR(weak[0].centroid.y(), 1.05, 1e-5);
  // Without a weak output (or with weak_min_points 0) the clusters are the same.
  std::vector<Cluster> plain;
  Clusterer(p).cluster(f, f.valid, plain);
  ASSERT_EQ(plain.size(), 1u);
  EXPECT_EQ(plain[0].pixels, out[0].pixels);
  for (int off : {0, 3, 4}) {  // 0 or min_points and above: no weak clusters
    p.weak_min_points = off;
    Clusterer(p).cluster(f, f.valid, out, &weak);
    EXPECT_EQ(out.size(), 1u);
    EXPECT_TRUE(weak.empty()) << off;
  }
}

TEST(Clusterer, NegativeWeakMinPointsIsAnErrorNamingTheKey) {
  ClusteringParams p;
  p.weak_min_points = -1;
  try {
    p.validate();
    FAIL() << "no error";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("weak_min_points"), std::string::npos) << e.what();
  }
}
