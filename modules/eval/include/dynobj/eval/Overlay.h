// SPDX-License-Identifier: BSD-3-Clause
// Overlay images: the intensity image with true positives in red, false positives in yellow and
// misses (false negatives) in blue, the tracked objects' ids beside them (without ground truth:
// the dynamic pixels in red); and a contact sheet.
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/core/LidarFrame.h>

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

namespace dynobj::eval {

/// BGR image, rows scaled by `row_scale` (64-row images are flat). `objects` may be empty.
/// Without ground truth (`truth` empty) the predicted pixels are red.
cv::Mat overlayImage(const core::LidarFrame& frame, const cv::Mat_<std::uint8_t>& predicted,
                     const cv::Mat_<std::uint8_t>& truth,
                     const std::vector<core::TrackedObject>& objects, int row_scale = 2);

/// The images stacked vertically, each with its caption on a dark band above it.
cv::Mat contactSheet(const std::vector<std::pair<std::string, cv::Mat>>& captioned);

}  // namespace dynobj::eval
