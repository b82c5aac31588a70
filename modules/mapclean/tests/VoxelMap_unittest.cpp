// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/VoxelMap.h>
#include <gtest/gtest.h>

#include <map>
#include <random>
#include <set>
#include <stdexcept>

using dynobj::mapclean::MapPoint;
using dynobj::mapclean::VoxelMap;

TEST(VoxelMap, OnePointPerVoxelAtTheCentroidWithMeanIntensity) {
  VoxelMap m(1.0);
  m.insert({0.2f, 0.2f, 0.2f, 10.f});
  m.insert({0.8f, 0.6f, 0.4f, 20.f});
  m.insert({1.5f, 0.5f, 0.5f, 7.f});   // next voxel in x
  m.insert({-0.5f, 0.5f, 0.5f, 3.f});  // negative side: its own voxel (floor, not truncation)
  EXPECT_EQ(m.size(), 3u);
  EXPECT_EQ(m.pointsInserted(), 4u);
  const auto p = m.points();  // ordered by voxel index: x = -1, 0, 1
  ASSERT_EQ(p.size(), 3u);
  EXPECT_FLOAT_EQ(p[0].x, -0.5f);
  EXPECT_FLOAT_EQ(p[1].x, 0.5f);
  EXPECT_FLOAT_EQ(p[1].y, 0.4f);
  EXPECT_FLOAT_EQ(p[1].z, 0.3f);
  EXPECT_FLOAT_EQ(p[1].intensity, 15.f);
  EXPECT_FLOAT_EQ(p[2].x, 1.5f);
}

TEST(VoxelMap, SizeDependsOnSpaceNotOnRepetitions) {
  VoxelMap m(0.1);
  for (int scan = 0; scan < 100; scan++)
    for (int i = 0; i < 10; i++)
      m.insert({0.05f + 0.1f * static_cast<float>(i), 0.05f, 0.05f, 1.f});
  EXPECT_EQ(m.size(), 10u);
  EXPECT_EQ(m.pointsInserted(), 1000u);
}

TEST(VoxelMap, ZeroVoxelKeepsEveryPointInOrder) {
  VoxelMap m(0.0);
  m.insert({1, 2, 3, 4});
  m.insert({1, 2, 3, 5});
  const auto p = m.points();
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[1].intensity, 5.f);
}

TEST(VoxelMap, BadSizeAndFarPointsAreErrors) {
  EXPECT_THROW(VoxelMap(-0.1), std::invalid_argument);
  VoxelMap m(0.01);
  EXPECT_THROW(m.insert({1e5f, 0, 0, 0}), std::out_of_range);  // 1e7 voxels > 2^20
  EXPECT_TRUE(m.empty());
}

TEST(VoxelMap, ExtractTakesTheVoxelsAskedForAndEveryOtherIsStillFound) {
  // Oracle: a plain map of key -> count. Voxels taken in several rounds (some of them, then all);
  // after each, every voxel left is found with its count and none taken is.
  VoxelMap m(0.1);
  std::map<std::uint64_t, std::uint32_t> truth;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> coord(-3.f, 3.f);
  for (int i = 0; i < 20000; i++) {
    const MapPoint p{coord(rng), coord(rng), coord(rng) * 0.1f, 1.f};
    m.insert(p, static_cast<std::uint32_t>(i / 1000));
    truth[m.keyOf(p.x, p.y, p.z)]++;
  }
  for (const std::uint32_t before : {5u, 12u, 1000u}) {
    const auto out = m.extract([&](const VoxelMap::Slot& s) { return s.cell.last < before; });
    for (std::size_t k = 1; k < out.size(); k++) EXPECT_LT(out[k - 1].key, out[k].key);
    for (const VoxelMap::Slot& s : out) {
      EXPECT_LT(s.cell.last, before);
      EXPECT_EQ(s.cell.n, truth.at(s.key));
      EXPECT_EQ(m.countAt(s.key), 0u);
      truth.erase(s.key);
    }
    ASSERT_EQ(m.size(), truth.size()) << "before " << before;
    for (const auto& [key, n] : truth) EXPECT_EQ(m.countAt(key), n);
  }
  EXPECT_TRUE(m.empty());
  m.insert({0.05f, 0.05f, 0.05f, 1.f});  // usable again after everything was taken
  EXPECT_EQ(m.size(), 1u);
}

TEST(VoxelMap, ExtractKeepsEveryProbeChainWhole) {
  // Dense tables (just under the growth threshold), a third of the voxels taken at random, many
  // times: every voxel left must still be found (a voxel re-seated past a gap is lost).
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> cell(-500, 500);
  for (int round = 0; round < 2000; round++) {
    VoxelMap m(1.0);
    std::map<std::uint64_t, std::uint32_t> truth;
    while (truth.size() < 700) {  // 1024 slots, 70 % full
      const MapPoint p{static_cast<float>(cell(rng)), static_cast<float>(cell(rng)), 0.5f, 1.f};
      m.insert(p);
      truth[m.keyOf(p.x, p.y, p.z)]++;
    }
    std::set<std::uint64_t> take;
    for (const auto& kv : truth)
      if (rng() % 3 == 0) take.insert(kv.first);
    const auto out = m.extract([&](const VoxelMap::Slot& s) { return take.count(s.key) > 0; });
    ASSERT_EQ(out.size(), take.size());
    for (const std::uint64_t key : take) truth.erase(key);
    ASSERT_EQ(m.size(), truth.size());
    for (const auto& [key, n] : truth) ASSERT_EQ(m.countAt(key), n) << "round " << round;
    for (const VoxelMap::Slot& s : out) {  // a voxel opened again starts from nothing
      const MapPoint p = m.centroid(s);
      m.insert(p, 99);
      ASSERT_EQ(m.countAt(s.key), 1u) << "round " << round;
      ASSERT_EQ(m.lastAt(s.key), 99u);
    }
  }
}
