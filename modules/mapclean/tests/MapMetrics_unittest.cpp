// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/MapMetrics.h>
#include <gtest/gtest.h>

#include <cmath>

using dynobj::mapclean::MapEvaluator;

TEST(MapMetrics, HandComputedCounts) {
  // Map: a wall point and a ghost (a person's point the cleaner missed).
  MapEvaluator e({{0, 0, 0, 0}, {1, 0, 0, 0}}, 0.1);
  e.add(0, 0, 0.05f, false);    // static, 5 cm from the wall point: kept
  e.add(5, 0, 0, false);        // static, nothing near: lost
  e.add(1, 0, 0.02f, true);     // dynamic, the ghost is 2 cm away: not removed
  e.add(3, 0, 0, true);         // dynamic, removed
  e.add(0.0f, 0.09f, 0, true);  // dynamic next to the wall point: not removed, but no ghost
  const auto s = e.scores();
  EXPECT_EQ(s.gt_static, 2u);
  EXPECT_EQ(s.static_kept, 1u);
  EXPECT_EQ(s.gt_dynamic, 3u);
  EXPECT_EQ(s.dynamic_removed, 1u);
  EXPECT_DOUBLE_EQ(*s.sa(), 0.5);
  EXPECT_DOUBLE_EQ(*s.da(), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(*s.aa(), std::sqrt(0.5 / 3.0));
  EXPECT_EQ(s.map_points, 2u);
  EXPECT_EQ(s.ghost_points, 1u);  // only the point at x = 1 is explained by dynamic GT alone
}

TEST(MapMetrics, ToleranceIsInclusive) {
  MapEvaluator e({{0, 0, 0, 0}}, 0.5);
  e.add(0.5f, 0, 0, false);
  e.add(0.5001f, 0, 0, false);
  EXPECT_EQ(e.scores().static_kept, 1u);
}

TEST(MapMetrics, EmptyCasesAreUndefinedNotZero) {
  MapEvaluator none({{0, 0, 0, 0}}, 0.05);
  EXPECT_FALSE(none.scores().sa());
  EXPECT_FALSE(none.scores().da());
  EXPECT_FALSE(none.scores().aa());

  MapEvaluator only_static({{0, 0, 0, 0}}, 0.05);
  only_static.add(0, 0, 0, false);
  EXPECT_DOUBLE_EQ(*only_static.scores().sa(), 1.0);
  EXPECT_FALSE(only_static.scores().da());
  EXPECT_FALSE(only_static.scores().aa());

  MapEvaluator empty_map({}, 0.05);  // everything removed
  empty_map.add(0, 0, 0, false);
  empty_map.add(1, 0, 0, true);
  EXPECT_DOUBLE_EQ(*empty_map.scores().sa(), 0.0);
  EXPECT_DOUBLE_EQ(*empty_map.scores().da(), 1.0);
  EXPECT_DOUBLE_EQ(*empty_map.scores().aa(), 0.0);
  EXPECT_EQ(empty_map.scores().ghost_points, 0u);
}

TEST(MapMetrics, BadToleranceIsAnError) {
  EXPECT_THROW(MapEvaluator({}, 0.0), std::invalid_argument);
}
