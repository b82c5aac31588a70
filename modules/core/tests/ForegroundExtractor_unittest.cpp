// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/ForegroundExtractor.h>
#include <gtest/gtest.h>

using namespace dynobj::core;

namespace {

/// A flat 20 x 60 intensity image of 100 with a 3 x 3 square of `square` at rows 8-10, cols 20-22.
LidarFrame squareFrame(float square) {
  SensorModel s;
  s.rows = 20;
  s.cols = 60;
  s.elevation_top = 0.3;
  s.elevation_bottom = -0.3;
  LidarFrame f(s);
  f.has_intensity = true;
  for (int r = 0; r < 20; r++)
    for (int c = 0; c < 60; c++) {
      const bool in = r >= 8 && r <= 10 && c >= 20 && c <= 22;
      f.setPixel(r, c, 5.0f, in ? square : 100.0f, cv::Vec3f(5, 0, 0), r * 60 + c);
    }
  return f;
}

}  // namespace

TEST(ForegroundExtractor, BrightSquareGivesExactlyItsPixels) {
  ForegroundParams p;
  p.absolute = false;  // the paper's t = B(f - h, theta)
  ForegroundExtractor fx(p);
  cv::Mat_<std::uint8_t> t;
  fx.extract(squareFrame(200), {}, t);
  for (int r = 0; r < 20; r++)
    for (int c = 0; c < 60; c++)
      EXPECT_EQ(t(r, c) != 0, r >= 8 && r <= 10 && c >= 20 && c <= 22) << r << "," << c;
}

TEST(ForegroundExtractor, AbsoluteModeFindsDarkObjects) {
  ForegroundParams paper;
  paper.absolute = false;
  ForegroundParams ours;  // default: |f - h| > theta
  cv::Mat_<std::uint8_t> t1, t2;
  ForegroundExtractor(paper).extract(squareFrame(10), {}, t1);
  ForegroundExtractor(ours).extract(squareFrame(10), {}, t2);
  EXPECT_EQ(cv::countNonZero(t1(cv::Rect(20, 8, 3, 3))), 0);  // darker: invisible to Eq. (4)
  EXPECT_EQ(cv::countNonZero(t2(cv::Rect(20, 8, 3, 3))), 9);
}

TEST(ForegroundExtractor, NoReturnsAndExcludedPixelsGiveNoFeatures) {
  LidarFrame f = squareFrame(100);                  // flat
  for (int c = 0; c < 60; c++) f.clearPixel(5, c);  // a row of no-returns must not create edges
  cv::Mat_<std::uint8_t> t;
  ForegroundExtractor().extract(f, {}, t);
  EXPECT_EQ(cv::countNonZero(t), 0);
  LidarFrame g = squareFrame(250);
  cv::Mat_<std::uint8_t> exclude(20, 60, std::uint8_t{0});
  exclude(cv::Rect(20, 8, 3, 3)).setTo(255);
  ForegroundExtractor().extract(g, exclude, t);
  EXPECT_EQ(cv::countNonZero(t(cv::Rect(20, 8, 3, 3))), 0);
}

TEST(ForegroundExtractor, WrapsAroundTheSeam) {
  ForegroundParams p;
  p.absolute = false;
  LidarFrame f = squareFrame(100);
  for (int r = 8; r <= 10; r++) f.intensity(r, 0) = 220;  // at column 0, next to column 59
  cv::Mat_<std::uint8_t> t;
  ForegroundExtractor(p).extract(f, {}, t);
  EXPECT_EQ(cv::countNonZero(t), 3);
  EXPECT_EQ(t(9, 0), 255);
}

TEST(ForegroundExtractor, ParametersValidateByKey) {
  ForegroundParams p;
  p.kernel_half_width = 0;
  try {
    p.validate();
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("kernel_half_width"), std::string::npos);
  }
}
