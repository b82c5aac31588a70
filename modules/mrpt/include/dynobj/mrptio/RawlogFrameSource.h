// SPDX-License-Identifier: BSD-3-Clause
// The LiDAR observations of a rawlog as Frames, one at a time (memory stays flat however long the
// file), with the latest odometry seen before each. For read-only tools; rawlog-to-rawlog filters
// use RawlogReader + DynamicObjectFilter (filterRawlog).
#pragma once

#include <cstddef>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "dynobj/mrptio/FrameSource.h"
#include "dynobj/mrptio/ObservationConverter.h"
#include "dynobj/mrptio/RawlogReader.h"

namespace dynobj::mrptio {

class RawlogFrameSource : public FrameSource {
 public:
  struct Options {
    std::string sensor_label;  ///< only observations with this label; empty = every LiDAR one
    std::size_t from = 0;      ///< first rawlog entry (0-based, inclusive)
    std::size_t to = std::numeric_limits<std::size_t>::max();  ///< last entry (inclusive)
  };

  /// Opens `rawlog` (throws RawlogError when it cannot).
  RawlogFrameSource(std::string rawlog, ObservationConverter converter, Options opts);

  /// Converts the next matching LiDAR observation into `f`. Returns false at the end of the
  /// file (or past `to`). Throws RawlogError / ConversionError.
  bool next(Frame& f) override;
  void rewind() override;
  /// Without converting the observation.
  bool nextTime(std::int64_t& timestamp_ns) override;
  /// Passes over earlier LiDAR observations without converting them.
  void skipBefore(std::int64_t timestamp_ns) override { skip_before_ns_ = timestamp_ns; }
  /// The share of the file's bytes read.
  double progress() const override { return reader_->fileFraction(); }
  std::string describe() const override { return "rawlog '" + path_ + "'"; }
  /// The --sensor-label asked for, and every label seen with its observation class.
  std::string noFramesDetail() const override;

  /// Every sensor label met so far, with its observation class (for "no such label" messages).
  const std::map<std::string, std::string>& labelsSeen() const { return labels_; }
  std::size_t entriesRead() const { return reader_->entriesRead(); }

 private:
  std::string path_;
  ObservationConverter converter_;
  Options opts_;
  std::unique_ptr<RawlogReader> reader_;
  RawlogEntry entry_;
  std::vector<mrpt::obs::CObservation::Ptr> pending_;
  std::size_t pending_pos_ = 0, frames_ = 0;
  std::optional<Eigen::Isometry3d> odometry_;
  std::map<std::string, std::string> labels_;
  std::int64_t skip_before_ns_ = std::numeric_limits<std::int64_t>::min();

  /// next() and nextTime(): the next matching LiDAR observation (not converted), or null at the
  /// end.
  mrpt::obs::CObservation::Ptr nextObservation();
};

}  // namespace dynobj::mrptio
