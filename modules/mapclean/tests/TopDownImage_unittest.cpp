// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/TopDownImage.h>
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

using dynobj::mapclean::drawLegendAndScale;
using dynobj::mapclean::LegendEntry;
using dynobj::mapclean::scaleBarLength;
using dynobj::mapclean::TopDownView;

TEST(TopDownImage, ScaleBarIsTheLargestRoundLengthWithinAFifthOfTheWidth) {
  EXPECT_DOUBLE_EQ(scaleBarLength(100.0), 20.0);  // a fifth: 20
  EXPECT_DOUBLE_EQ(scaleBarLength(99.0), 10.0);   // 19.8: 10
  EXPECT_DOUBLE_EQ(scaleBarLength(30.0), 5.0);    // 6: 5
  EXPECT_DOUBLE_EQ(scaleBarLength(9.0), 1.0);     // 1.8: 1
  EXPECT_DOUBLE_EQ(scaleBarLength(2.6), 0.5);     // 0.52: 0.5
  EXPECT_DOUBLE_EQ(scaleBarLength(1000.0), 200.0);
  EXPECT_DOUBLE_EQ(scaleBarLength(0.0), 0.01);
}

TEST(TopDownImage, ScaleBarSpansItsLengthInPixels) {
  TopDownView view;
  view.resolution = 0.1;  // 400 px = 40 m wide: a 5 m bar of 50 px
  view.width = 400;
  view.height = 200;
  cv::Mat img(view.height, view.width, CV_8UC3, cv::Scalar(0, 0, 0));
  drawLegendAndScale(img, view, {});
  // The bar is the one row near the bottom with a run of white pixels; measure the run.
  int longest = 0;
  for (int r = img.rows - 20; r < img.rows; r++) {
    int run = 0;
    for (int c = 0; c < img.cols; c++) {
      run = img.at<cv::Vec3b>(r, c) == cv::Vec3b(255, 255, 255) ? run + 1 : 0;
      longest = std::max(longest, run);
    }
  }
  EXPECT_EQ(longest, 50);
  // Nothing is drawn above the scale bar's box (no legend given).
  EXPECT_EQ(cv::countNonZero(img.rowRange(0, 100).reshape(1)), 0);
}

TEST(TopDownImage, LegendShowsEachSwatchInItsColour) {
  TopDownView view;
  view.resolution = 0.05;
  cv::Mat img(300, 400, CV_8UC3, cv::Scalar(0, 0, 0));
  drawLegendAndScale(img, view,
                     {{cv::Scalar(0, 0, 255), "dynamic"}, {cv::Scalar(0, 255, 0), "other"}});
  // The swatches: 12 x 10 px squares at (6, 9) and (6, 27) (centres), in their colours.
  EXPECT_EQ(img.at<cv::Vec3b>(14, 12), cv::Vec3b(0, 0, 255));
  EXPECT_EQ(img.at<cv::Vec3b>(32, 12), cv::Vec3b(0, 255, 0));
}

TEST(TopDownImage, TooSmallAnImageIsLeftAlone) {
  TopDownView view;
  cv::Mat img(60, 100, CV_8UC3, cv::Scalar(0, 0, 0));
  drawLegendAndScale(img, view, {{cv::Scalar(0, 0, 255), "dynamic"}});
  EXPECT_EQ(cv::countNonZero(img.reshape(1)), 0);
}
