// SPDX-License-Identifier: BSD-3-Clause
// Ground truth (label file v1) aligned with frames the one way every tool does it: by timestamp,
// the image sizes equal. Errors name the file, the time and the frame. Also reads label files used
// as a classification (dynobj-mapclean --labels): then the role in messages is "label file" and
// sweeps nobody reviewed are accepted.
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/io/LabelFile.h>

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <utility>

namespace dynobj::mrptio {

class GroundTruth {
 public:
  struct Options {
    std::string role = "ground truth";  ///< what the file is, in messages
    bool require_reviewed = true;       ///< refuse a file with unreviewed sweeps (ground truth)
  };
  /// Reads the whole file (throws io::LabelFileError).
  explicit GroundTruth(std::string file) : GroundTruth(std::move(file), Options{}) {}
  GroundTruth(std::string file, Options opts);

  /// The sweep at `frame`'s time and its index. Throws std::runtime_error when there is none
  /// ("...: the timestamps do not match") or the sizes differ (naming the frame and its time).
  /// `frame_index` is for messages.
  const io::LabelSweep& sweep(const core::LidarFrame& frame, std::size_t frame_index,
                              std::size_t* index = nullptr) const;
  /// sweep() as a mask of the frame's size (255 = dynamic).
  cv::Mat_<std::uint8_t> mask(const core::LidarFrame& frame, std::size_t frame_index) const;

  const io::LabelFile& labels() const { return labels_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  Options opts_;
  io::LabelFile labels_;
  std::map<std::int64_t, std::size_t> by_time_;
};

}  // namespace dynobj::mrptio
