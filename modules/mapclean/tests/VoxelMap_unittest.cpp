// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/VoxelMap.h>
#include <gtest/gtest.h>

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
