// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/FrameImages.h>
#include <gtest/gtest.h>

using namespace dynobj::io;

TEST(FrameImages, PercentileStretchIsLinearAndKeepsNoReturnsBlack) {
  cv::Mat_<float> img(1, 4);
  img << 10, 20, 30, 1000;
  cv::Mat_<std::uint8_t> mask(1, 4);
  mask << 255, 255, 255, 0;
  const auto out = stretchToU8(img, mask, 0.0, 100.0);
  EXPECT_EQ(out(0, 0), 1);    // lowest return -> 1, never 0
  EXPECT_EQ(out(0, 1), 128);  // 1 + (20-10) * 254/20
  EXPECT_EQ(out(0, 2), 255);
  EXPECT_EQ(out(0, 3), 0);  // masked out
}

TEST(FrameImages, ScaleRowsRepeatsRows) {
  cv::Mat_<std::uint8_t> img(2, 3);
  img << 1, 2, 3, 4, 5, 6;
  const cv::Mat_<std::uint8_t> out = scaleRows(img, 3);
  ASSERT_EQ(out.rows, 6);
  EXPECT_EQ(out(2, 1), 2);
  EXPECT_EQ(out(3, 1), 5);
}

TEST(FrameImages, NoIntensityFallsBackToRange) {
  dynobj::core::SensorModel s;
  s.rows = 2;
  s.cols = 8;
  dynobj::core::LidarFrame f(s);
  f.setPixel(0, 0, 1.0f, 0.0f, cv::Vec3f(1, 0, 0), 0);
  f.setPixel(0, 1, 3.0f, 0.0f, cv::Vec3f(3, 0, 0), 1);
  f.has_intensity = false;
  const auto out = intensityToU8(f);
  EXPECT_LT(out(0, 0), out(0, 1));
  EXPECT_EQ(out(1, 0), 0);
}
