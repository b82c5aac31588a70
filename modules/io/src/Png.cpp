// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/Png.h"

#include <dynobj/io/FrameImages.h>

#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "dynobj/io/AtomicFile.h"

namespace dynobj::io {

void writePng(const std::string& path, const cv::Mat& image) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, image);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
  if (!ok) throw std::runtime_error(cannotWriteMessage(path));
}

void writePngAtomically(const std::string& path, const cv::Mat& image) {
  PartialPath file(path, ".png");  // OpenCV picks the codec by the extension
  bool ok = false;
  try {
    ok = cv::imwrite(file.partial(), image);
  } catch (const cv::Exception& e) {
    throw std::runtime_error("cannot write '" + path + "': " + e.what());
  }
  if (!ok) throw std::runtime_error(cannotWriteMessage(path));
  file.commit();
}

void writeFramePngs(const core::LidarFrame& frame, const std::string& prefix, int row_scale) {
  writePng(prefix + "range.png", io::scaleRows(io::rangeToColor(frame), row_scale));
  writePng(prefix + "intensity.png", io::scaleRows(io::intensityToU8(frame), row_scale));
}

}  // namespace dynobj::io
