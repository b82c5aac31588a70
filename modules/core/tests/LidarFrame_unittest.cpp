// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/LidarFrame.h>
#include <gtest/gtest.h>

using dynobj::core::LidarFrame;
using dynobj::core::SensorModel;

TEST(LidarFrame, ResetSizesAndEmptiesTheGrid) {
  SensorModel s;
  s.rows = 16;
  s.cols = 32;
  LidarFrame f(s);
  EXPECT_EQ(f.rows(), 16);
  EXPECT_EQ(f.cols(), 32);
  EXPECT_EQ(f.pixelCount(), 512u);
  EXPECT_EQ(f.validCount(), 0u);
  f.setPixel(3, 4, 2.0f, 9.0f, cv::Vec3f(2, 0, 0), 11);
  EXPECT_TRUE(f.isValid(3, 4));
  EXPECT_EQ(f.validCount(), 1u);
  EXPECT_EQ(f.pixelIndex(3, 4), 3 * 32 + 4);
  const float* before = f.range.ptr<float>(0);
  f.reset(s);  // same size: memory reused, content cleared
  EXPECT_EQ(f.range.ptr<float>(0), before);
  EXPECT_EQ(f.validCount(), 0u);
  EXPECT_EQ(f.source_index(3, 4), -1);
  f.setPixel(0, 0, 1.0f, 1.0f, cv::Vec3f(1, 0, 0), 0);
  f.clearPixel(0, 0);
  EXPECT_FALSE(f.isValid(0, 0));
  EXPECT_EQ(f.source_index(0, 0), -1);
}

TEST(LidarFrame, PointMaskRejectsWrongSize) {
  SensorModel s;
  s.rows = 4;
  s.cols = 8;
  LidarFrame f(s);
  f.point_pixel = {0, 9, -1};
  cv::Mat_<std::uint8_t> good(4, 8, std::uint8_t{0});
  good(1, 1) = 255;
  EXPECT_EQ(f.pointMaskFromPixelMask(good), (std::vector<std::uint8_t>{0, 1, 0}));
  cv::Mat_<std::uint8_t> bad(5, 8, std::uint8_t{0});
  EXPECT_THROW(f.pointMaskFromPixelMask(bad), std::invalid_argument);
}
