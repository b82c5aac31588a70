// SPDX-License-Identifier: BSD-3-Clause
// 8-bit renderings of a LidarFrame for people and for OpenCV feature detectors (writing them as
// PNG files: dynobj/io/Png.h).
#pragma once

#include <dynobj/core/LidarFrame.h>

#include <opencv2/core.hpp>

namespace dynobj::io {

/// Linear percentile stretch of the pixels under `mask` (non-zero): the lo_pct percentile maps
/// to 1, the hi_pct percentile to 255 (clamped); pixels outside the mask are 0, so a no-return
/// is never confused with a dark return. Works for any sensor's units.
cv::Mat_<std::uint8_t> stretchToU8(const cv::Mat_<float>& image, const cv::Mat_<std::uint8_t>& mask,
                                   double lo_pct = 1.0, double hi_pct = 99.0);

/// Range image, near = warm colours (TURBO colour map scaled to [0, max_range]); no return = black.
cv::Mat rangeToColor(const core::LidarFrame& frame, double max_range);
/// rangeToColor scaled to the 98th percentile of the frame's ranges (indoor and outdoor scans
/// both use the whole colour map); the sensor's max range when the frame has no return.
cv::Mat rangeToColor(const core::LidarFrame& frame);

/// Intensity image stretched with stretchToU8; the range image when the frame has no intensity.
cv::Mat_<std::uint8_t> intensityToU8(const core::LidarFrame& frame);

/// Grey image (CV_8U) -> BGR with the pixels of `mask` (non-zero) painted in `bgr`.
cv::Mat overlayMask(const cv::Mat_<std::uint8_t>& gray, const cv::Mat_<std::uint8_t>& mask,
                    const cv::Scalar& bgr = cv::Scalar(0, 0, 255));

/// Repeats each row `row_scale` times (nearest neighbour) so that a 16- or 64-row image is
/// readable on screen.
cv::Mat scaleRows(const cv::Mat& image, int row_scale);

}  // namespace dynobj::io
