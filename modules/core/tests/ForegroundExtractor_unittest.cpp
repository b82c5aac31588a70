// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/ForegroundExtractor.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

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

// Oracle: the stretch's percentiles (histogram of order keys + selection in one bin) are the
// values a full sort of the same every-3rd-valid-pixel sample puts at their ranks, on intensities
// with negatives, signed zeros, ties and a long tail, and with no returns in between.
TEST(ForegroundExtractor, StretchPercentilesMatchAFullSort) {
  SensorModel s;
  s.rows = 32;
  s.cols = 500;
  s.elevation_top = 0.3;
  s.elevation_bottom = -0.3;
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; trial++) {
    LidarFrame f(s);
    f.has_intensity = true;
    std::uniform_real_distribution<float> u(-50.0f, 50.0f);
    std::exponential_distribution<float> tail(0.01f);
    for (int r = 0; r < s.rows; r++)
      for (int c = 0; c < s.cols; c++) {
        if ((r * 7 + c * 3 + trial) % 11 == 0) continue;  // no return here
        const int kind = (r + c + trial) % 5;
        const float v = kind == 0   ? u(rng)
                        : kind == 1 ? std::round(u(rng) / 10.0f) * 10.0f  // ties
                        : kind == 2 ? (c % 2 ? 0.0f : -0.0f)
                                    : tail(rng);
        f.setPixel(r, c, 5.0f, v, cv::Vec3f(5, 0, 0), r * s.cols + c);
      }
    ForegroundParams p;
    p.stretch_low = 1 + trial % 4;
    p.stretch_high = 99 - trial % 3;
    ForegroundExtractor fe(p);
    const cv::Mat_<float>& out = fe.normalize(f);

    std::vector<float> sample;
    const int n = s.rows * s.cols;
    for (int i = 0; i < n; i += 3)
      if (f.valid(i / s.cols, i % s.cols)) sample.push_back(f.intensity(i / s.cols, i % s.cols));
    std::sort(sample.begin(), sample.end());
    const auto at = [&](double q) {
      return static_cast<double>(
          sample[static_cast<std::size_t>(q / 100.0 * static_cast<double>(sample.size() - 1))]);
    };
    const double lo = at(p.stretch_low), hi = at(p.stretch_high);
    const double scale = 191.0 / std::max(hi - lo, 0.01 * std::abs(hi) + 1e-3);
    for (int i = 0; i < n; i++) {
      const int r = i / s.cols, c = i % s.cols;
      const float want =
          f.valid(r, c)
              ? static_cast<float>(std::clamp(32.0 + (f.intensity(r, c) - lo) * scale, 0.0, 255.0))
              : 0.0f;
      ASSERT_EQ(out(r, c), want) << "trial " << trial << " pixel (" << r << ", " << c << ")";
    }
  }
}
