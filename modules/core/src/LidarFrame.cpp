// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/LidarFrame.h"

#include <stdexcept>
#include <string>

namespace dynobj::core {

void LidarFrame::reset(const SensorModel& s) {
  sensor = s;
  range.create(s.rows, s.cols);
  intensity.create(s.rows, s.cols);
  xyz.create(s.rows, s.cols);
  valid.create(s.rows, s.cols);
  source_index.create(s.rows, s.cols);
  clear();
}

void LidarFrame::clear() {
  range.setTo(0);
  intensity.setTo(0);
  xyz.setTo(cv::Vec3f(0, 0, 0));
  valid.setTo(0);
  source_index.setTo(-1);
  point_pixel.clear();
  timestamp_ns = 0;
  has_intensity = false;
}

std::size_t LidarFrame::validCount() const {
  return static_cast<std::size_t>(cv::countNonZero(valid));
}

void LidarFrame::setPixel(int r, int c, float rng, float inten, const cv::Vec3f& p,
                          std::int32_t src) {
  range(r, c) = rng;
  intensity(r, c) = inten;
  xyz(r, c) = p;
  valid(r, c) = 255;
  source_index(r, c) = src;
}

void LidarFrame::clearPixel(int r, int c) {
  range(r, c) = 0;
  intensity(r, c) = 0;
  xyz(r, c) = cv::Vec3f(0, 0, 0);
  valid(r, c) = 0;
  source_index(r, c) = -1;
}

std::vector<std::uint8_t> LidarFrame::pointMaskFromPixelMask(
    const cv::Mat_<std::uint8_t>& pixel_mask) const {
  if (pixel_mask.rows != rows() || pixel_mask.cols != cols())
    throw std::invalid_argument("pointMaskFromPixelMask: mask is " +
                                std::to_string(pixel_mask.rows) + "x" +
                                std::to_string(pixel_mask.cols) + ", frame is " +
                                std::to_string(rows()) + "x" + std::to_string(cols()));
  std::vector<std::uint8_t> out(point_pixel.size(), 0);
  const std::uint8_t* m = pixel_mask.ptr<std::uint8_t>(0);
  const bool continuous = pixel_mask.isContinuous();
  for (std::size_t i = 0; i < point_pixel.size(); i++) {
    const std::int32_t px = point_pixel[i];
    if (px < 0) continue;
    const std::uint8_t v = continuous ? m[px] : pixel_mask(px / cols(), px % cols());
    out[i] = v != 0 ? 1 : 0;
  }
  return out;
}

}  // namespace dynobj::core
