// SPDX-License-Identifier: BSD-3-Clause
// One LiDAR sweep as an organized H x W grid (row = beam, column = azimuth bin): the data every
// stage of the detector works on. Each pixel keeps the index of the input point it came from and
// each input point keeps its pixel, so per-pixel results map back to the input without loss.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "dynobj/core/SensorModel.h"

namespace dynobj::core {

struct LidarFrame {
  SensorModel sensor;             ///< geometry the grid was built for (rows x cols)
  std::int64_t timestamp_ns = 0;  ///< sweep time [ns since the Unix epoch]
  bool has_intensity = false;     ///< false: the source had no intensity (stages use range)

  cv::Mat_<float> range;                ///< [m] Euclidean range, 0 = no return
  cv::Mat_<float> intensity;            ///< sensor units; 0 where no return or no intensity
  cv::Mat_<cv::Vec3f> xyz;              ///< [m] point in the sensor frame, (0,0,0) where no return
  cv::Mat_<std::uint8_t> valid;         ///< 255 = return, 0 = none (usable as an OpenCV mask)
  cv::Mat_<std::int32_t> source_index;  ///< index of the input point shown here, -1 = none

  /// For every input point, the pixel (row * cols + col) it fell in, or -1 when it is not in the
  /// image (invalid coordinates or outside the field of view). Several points may share a pixel:
  /// the pixel shows the nearest one; the others are still mapped to it.
  std::vector<std::int32_t> point_pixel;

  LidarFrame() = default;
  explicit LidarFrame(const SensorModel& s) { reset(s); }

  /// Sizes the grid for `s` (reusing memory when the size is unchanged) and empties it.
  void reset(const SensorModel& s);
  /// Empties every pixel and the point map; keeps the allocation.
  void clear();

  int rows() const { return range.rows; }
  int cols() const { return range.cols; }
  std::size_t pixelCount() const { return range.total(); }
  bool isValid(int r, int c) const { return valid(r, c) != 0; }
  int pixelIndex(int r, int c) const { return r * cols() + c; }
  /// The point at pixel index `px` (row * cols + col), without dividing by cols when the grid is
  /// one block of memory (always, unless a caller made it a view of a larger image).
  const cv::Vec3f& pointAt(int px) const {
    return xyz.isContinuous() ? xyz.ptr<cv::Vec3f>(0)[px] : xyz(px / cols(), px % cols());
  }
  std::size_t validCount() const;
  std::size_t sourcePointCount() const { return point_pixel.size(); }

  /// Stores a return at (r, c): range, intensity, point and source index.
  void setPixel(int r, int c, float rng, float inten, const cv::Vec3f& p, std::int32_t src);
  /// Removes the return at (r, c).
  void clearPixel(int r, int c);

  /// Maps a per-pixel mask (H x W, non-zero = set) to a per-input-point mask (0/1), including
  /// the points hidden behind a nearer one in the same pixel.
  std::vector<std::uint8_t> pointMaskFromPixelMask(const cv::Mat_<std::uint8_t>& pixel_mask) const;
};

}  // namespace dynobj::core
