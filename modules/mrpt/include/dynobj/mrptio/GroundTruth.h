// SPDX-License-Identifier: BSD-3-Clause
// Ground truth (label file v1) aligned with frames the one way every tool does it: by timestamp,
// the image sizes equal. Errors name the file, the time and the frame.
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/io/LabelFile.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace dynobj::mrptio {

class GroundTruth {
 public:
  /// Reads the whole file (throws io::LabelFileError).
  explicit GroundTruth(std::string file);

  /// The sweep at `frame`'s time and its index. Throws std::runtime_error when there is none
  /// ("...: the timestamps do not match") or the sizes differ. `frame_index` is for messages.
  const io::LabelSweep& sweep(const core::LidarFrame& frame, std::size_t frame_index,
                              std::size_t* index = nullptr) const;
  /// sweep() as a mask of the frame's size (255 = dynamic).
  cv::Mat_<std::uint8_t> mask(const core::LidarFrame& frame, std::size_t frame_index) const;

  const io::LabelFile& labels() const { return labels_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  io::LabelFile labels_;
  std::map<std::int64_t, std::size_t> by_time_;
};

}  // namespace dynobj::mrptio
