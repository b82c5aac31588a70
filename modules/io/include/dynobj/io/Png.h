// SPDX-License-Identifier: BSD-3-Clause
// PNG files of images and LidarFrames (the renderings themselves: dynobj/io/FrameImages.h).
#pragma once

#include <dynobj/core/LidarFrame.h>

#include <opencv2/core.hpp>
#include <string>

namespace dynobj::io {

/// cv::imwrite that throws std::runtime_error naming the path on failure.
void writePng(const std::string& path, const cv::Mat& image);

/// writePng through a PartialPath: a PNG under `path` is always complete.
void writePngAtomically(const std::string& path, const cv::Mat& image);

/// Writes <prefix>range.png (io::rangeToColor) and <prefix>intensity.png (io::intensityToU8),
/// rows repeated `row_scale` times. Throws std::runtime_error naming the file on failure.
void writeFramePngs(const core::LidarFrame& frame, const std::string& prefix, int row_scale = 1);

}  // namespace dynobj::io
