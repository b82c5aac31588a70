// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/FrameImages.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace dynobj::io {
namespace {

double percentile(std::vector<float>& values, double pct) {
  if (values.empty()) return 0.0;
  const double pos = std::clamp(pct, 0.0, 100.0) / 100.0 * static_cast<double>(values.size() - 1);
  const auto k = static_cast<std::size_t>(std::llround(pos));
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

}  // namespace

cv::Mat_<std::uint8_t> stretchToU8(const cv::Mat_<float>& image, const cv::Mat_<std::uint8_t>& mask,
                                   double lo_pct, double hi_pct) {
  CV_Assert(image.size() == mask.size());
  std::vector<float> values;
  values.reserve(image.total());
  for (int r = 0; r < image.rows; r++)
    for (int c = 0; c < image.cols; c++)
      if (mask(r, c)) values.push_back(image(r, c));
  cv::Mat_<std::uint8_t> out(image.size(), 0);
  if (values.empty()) return out;
  const double lo = percentile(values, lo_pct);
  double hi = percentile(values, hi_pct);
  if (hi <= lo) hi = lo + 1e-6;
  const double scale = 254.0 / (hi - lo);
  for (int r = 0; r < image.rows; r++)
    for (int c = 0; c < image.cols; c++)
      if (mask(r, c))
        out(r, c) = static_cast<std::uint8_t>(
            1.0 + std::clamp((static_cast<double>(image(r, c)) - lo) * scale, 0.0, 254.0));
  return out;
}

cv::Mat rangeToColor(const core::LidarFrame& frame, double max_range) {
  cv::Mat_<std::uint8_t> gray(frame.range.size(), 0);
  const double scale = 255.0 / std::max(max_range, 1e-3);
  for (int r = 0; r < frame.rows(); r++)
    for (int c = 0; c < frame.cols(); c++)
      if (frame.isValid(r, c))
        gray(r, c) = static_cast<std::uint8_t>(
            255.0 - std::clamp(static_cast<double>(frame.range(r, c)) * scale, 0.0, 254.0));
  cv::Mat color;
  cv::applyColorMap(gray, color, cv::COLORMAP_TURBO);
  color.setTo(cv::Scalar(0, 0, 0), frame.valid == 0);
  return color;
}

cv::Mat_<std::uint8_t> intensityToU8(const core::LidarFrame& frame) {
  return stretchToU8(frame.has_intensity ? frame.intensity : frame.range, frame.valid);
}

cv::Mat overlayMask(const cv::Mat_<std::uint8_t>& gray, const cv::Mat_<std::uint8_t>& mask,
                    const cv::Scalar& bgr) {
  CV_Assert(gray.size() == mask.size());
  cv::Mat out;
  cv::cvtColor(gray, out, cv::COLOR_GRAY2BGR);
  out.setTo(bgr, mask != 0);
  return out;
}

cv::Mat scaleRows(const cv::Mat& image, int row_scale) {
  if (row_scale <= 1) return image;
  cv::Mat out;
  cv::resize(image, out, cv::Size(image.cols, image.rows * row_scale), 0, 0, cv::INTER_NEAREST);
  return out;
}

cv::Mat rangeToColor(const core::LidarFrame& frame) {
  // Colour scale: the 98th percentile of the frame's ranges, so indoor and outdoor scans both use
  // the whole colour map.
  std::vector<float> ranges;
  ranges.reserve(frame.validCount());
  for (int r = 0; r < frame.rows(); r++)
    for (int c = 0; c < frame.cols(); c++)
      if (frame.isValid(r, c)) ranges.push_back(frame.range(r, c));
  return rangeToColor(frame, ranges.empty() ? frame.sensor.max_range : percentile(ranges, 98.0));
}

}  // namespace dynobj::io
