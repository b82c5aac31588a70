// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/GroundSegmenter.h>
#include <gtest/gtest.h>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Scene;

TEST(GroundSegmenter, FloorIsGroundObjectsAndWallsAreNot) {
  Scene scene;
  scene.posts.push_back({4, 0, 0.3, 1.8});
  const auto s = dynobj::test::smallSensor();
  const LidarFrame f = dynobj::test::render(scene, s);
  cv::Mat_<std::uint8_t> ground;
  const double z = GroundSegmenter().segment(f, ground);
  EXPECT_NEAR(z, -1.0, 1e-4);
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++) {
      if (!f.isValid(r, c)) continue;
      // Floor, or the last few cm of an object's base (within max_step / 2 of the ground height:
      // a height no segmenter can tell from the floor).
      const bool floor = f.xyz(r, c)[2] < -1.0f + 0.04f;
      EXPECT_EQ(ground(r, c) != 0, floor) << r << "," << c << " z=" << f.xyz(r, c)[2];
    }
}
