// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/GroundTruth.h"

#include <stdexcept>

namespace dynobj::mrptio {

GroundTruth::GroundTruth(std::string file, Options opts)
    : file_(std::move(file)), opts_(std::move(opts)), labels_(io::LabelFile::read(file_)) {
  if (opts_.require_reviewed) labels_.requireReviewed(file_);  // unchecked labels: no ground truth
  for (std::size_t i = 0; i < labels_.sweeps.size(); i++)
    by_time_[labels_.sweeps[i].timestamp_ns] = i;
}

const io::LabelSweep& GroundTruth::sweep(const core::LidarFrame& f, std::size_t frame_index,
                                         std::size_t* index) const {
  const auto it = by_time_.find(f.timestamp_ns);
  if (it == by_time_.end())
    throw std::runtime_error("'" + file_ + "': " + opts_.role + " has no sweep at " +
                             std::to_string(f.timestamp_ns) + " ns (frame " +
                             std::to_string(frame_index) + "): the timestamps do not match");
  if (labels_.rows != f.rows() || labels_.cols != f.cols())
    throw std::runtime_error("'" + file_ + "': " + opts_.role + " is " +
                             std::to_string(labels_.rows) + "x" + std::to_string(labels_.cols) +
                             " but the scans are " + std::to_string(f.rows()) + "x" +
                             std::to_string(f.cols()) + " (frame " + std::to_string(frame_index) +
                             " at " + std::to_string(f.timestamp_ns) + " ns)");
  if (index) *index = it->second;
  return labels_.sweeps[it->second];
}

cv::Mat_<std::uint8_t> GroundTruth::mask(const core::LidarFrame& f, std::size_t frame_index) const {
  return io::maskOfPixels(sweep(f, frame_index).pixels, f.rows(), f.cols());
}

}  // namespace dynobj::mrptio
