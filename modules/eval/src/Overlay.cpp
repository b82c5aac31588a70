// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/Overlay.h"

#include <dynobj/core/SphericalProjection.h>
#include <dynobj/io/FrameImages.h>

#include <opencv2/imgproc.hpp>

namespace dynobj::eval {

cv::Mat overlayImage(const core::LidarFrame& frame, const cv::Mat_<std::uint8_t>& predicted,
                     const cv::Mat_<std::uint8_t>& truth,
                     const std::vector<core::TrackedObject>& objects, int row_scale) {
  cv::Mat img;
  if (truth.empty()) {
    img = io::overlayMask(io::intensityToU8(frame), predicted, {0, 0, 255});
  } else {
    img = io::overlayMask(io::intensityToU8(frame), predicted & truth, {0, 0, 255});
    img.setTo(cv::Scalar(0, 255, 255), predicted & ~truth);  // false positive: yellow
    img.setTo(cv::Scalar(255, 0, 0), truth & ~predicted);    // miss: blue
  }
  img = io::scaleRows(img, row_scale);
  if (img.cols < 1024) {  // narrow scans (512 columns): twice as large, pixels kept sharp
    cv::resize(img, img, {}, 2, 2, cv::INTER_NEAREST);
    row_scale *= 2;
  }
  const int col_scale = img.cols / frame.cols();
  const core::SphericalProjection projection(frame.sensor);
  for (const core::TrackedObject& o : objects) {
    if (!o.dynamic) continue;
    int r = 0, c = 0;
    if (!projection.pixelOf(o.centroid.x(), o.centroid.y(), o.box_max.z(), r, c)) continue;
    const cv::Point at(std::min(c * col_scale + 4, img.cols - 24), std::max(r * row_scale - 4, 10));
    cv::putText(img, std::to_string(o.id), at, cv::FONT_HERSHEY_PLAIN, 0.9, {0, 0, 0}, 3);
    cv::putText(img, std::to_string(o.id), at, cv::FONT_HERSHEY_PLAIN, 0.9, {255, 255, 255}, 1);
  }
  return img;
}

cv::Mat contactSheet(const std::vector<std::pair<std::string, cv::Mat>>& captioned) {
  constexpr int kBand = 22;
  int width = 0, height = 0;
  for (const auto& [caption, img] : captioned) {
    width = std::max(width, img.cols);
    height += img.rows + kBand;
  }
  cv::Mat sheet(std::max(height, 1), std::max(width, 1), CV_8UC3, cv::Scalar(40, 40, 40));
  int y = 0;
  for (const auto& [caption, img] : captioned) {
    cv::putText(sheet, caption, {6, y + 16}, cv::FONT_HERSHEY_SIMPLEX, 0.5, {255, 255, 255}, 1);
    img.copyTo(sheet(cv::Rect(0, y + kBand, img.cols, img.rows)));
    y += img.rows + kBand;
  }
  return sheet;
}

}  // namespace dynobj::eval
