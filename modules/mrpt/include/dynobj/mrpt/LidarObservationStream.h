// SPDX-License-Identifier: BSD-3-Clause
// Reads a rawlog and yields its LiDAR observations as LidarFrames, one at a time (memory stays
// flat however long the file). For read-only tools; rawlog-to-rawlog filters use RawlogReader.
#pragma once

#include <cstddef>
#include <limits>
#include <map>
#include <string>

#include "dynobj/mrpt/ObservationConverter.h"
#include "dynobj/mrpt/RawlogReader.h"

namespace dynobj::mrpt {

class LidarObservationStream {
 public:
  struct Options {
    std::string sensor_label;  ///< only observations with this label; empty = every LiDAR one
    std::size_t from = 0;      ///< first rawlog entry (0-based, inclusive)
    std::size_t to = std::numeric_limits<std::size_t>::max();  ///< last entry (inclusive)
  };

  struct Item {
    std::size_t entry = 0;  ///< rawlog entry index
    ::mrpt::obs::CObservation::Ptr observation;
    core::LidarFrame frame;  ///< reused from one call to the next
    core::ProjectionStats stats;
  };

  LidarObservationStream(const std::string& rawlog, ObservationConverter converter, Options opts);

  /// Converts the next matching LiDAR observation into `item`. Returns false at the end of the
  /// file (or past `to`). Throws RawlogError / ConversionError.
  bool next(Item& item);

  /// Every sensor label met so far, with its observation class (for "no such label" messages).
  const std::map<std::string, std::string>& labelsSeen() const { return labels_; }
  std::size_t entriesRead() const { return reader_.entriesRead(); }

 private:
  RawlogReader reader_;
  ObservationConverter converter_;
  Options opts_;
  RawlogEntry entry_;
  std::vector<::mrpt::obs::CObservation::Ptr> pending_;
  std::size_t pending_pos_ = 0;
  std::map<std::string, std::string> labels_;
};

}  // namespace dynobj::mrpt
