// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/core/FreeSpaceCheck.h>
#include <gtest/gtest.h>

using namespace dynobj::core;

TEST(FreeSpaceEvidence, ASlidingClusterMustShowMoreFreeSpace) {
  // A see-through fence beside the path slides with the sensor: 6 of its 10 decisive points are
  // seen through (free). Enough for a walker (min_free_ratio 0.5), not for a cluster that slides
  // along itself like a wall's visible part (slide_free_ratio 0.75); a car shows 9 of 10.
  const FreeSpaceParams p;
  FreeSpaceEvidence fence;
  fence.free = 6;
  fence.occupied = 4;
  EXPECT_TRUE(fence.provesMotion(p));
  EXPECT_TRUE(fence.supportsMotion(p));
  EXPECT_FALSE(fence.provesMotion(p, true));
  EXPECT_FALSE(fence.supportsMotion(p, true));
  FreeSpaceEvidence car;
  car.free = 9;
  car.occupied = 1;
  EXPECT_TRUE(car.provesMotion(p, true));
  FreeSpaceEvidence little;  // too little evidence: no verdict either way
  little.free = 2;
  EXPECT_TRUE(little.supportsMotion(p, true));
  EXPECT_FALSE(little.provesMotion(p, true));
  FreeSpaceParams off = p;  // at or below min_free_ratio: the same test as any cluster
  off.slide_free_ratio = 0;
  EXPECT_TRUE(fence.provesMotion(off, true));
  FreeSpaceParams bad = p;
  bad.slide_free_ratio = 1.5;
  EXPECT_THROW(bad.validate(), ParameterError);
}
