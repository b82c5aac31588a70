// SPDX-License-Identifier: BSD-3-Clause
// Random access to the LiDAR sweeps of a rawlog without holding them: one pass records where each
// sweep's entry starts (its byte offset in the uncompressed stream), its time and the odometry seen
// before it; read(k) then seeks there and converts that one observation. Memory: ~200 bytes per
// sweep (a one-hour 10 Hz recording: 7 MB) plus, for a gzip rawlog, a copy of the decompressor's
// state every 32 MB of uncompressed data (~40 kB each: ~25 MB for 20 GB); seeking is instant in a
// plain rawlog and costs at most 32 MB of decompression in a gzip one, in either direction.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/mrptio/FrameSource.h"
#include "dynobj/mrptio/ObservationConverter.h"

namespace dynobj::mrptio {

class RawlogIndex {
 public:
  struct Options {
    std::string sensor_label;  ///< only this LiDAR; empty = the first one met (others: an error)
    /// Called every few hundred entries during the indexing pass (entries read, bytes read).
    std::function<void(std::size_t, std::uint64_t)> progress;
    /// gzip rawlogs: keep the decompressor's state every this many uncompressed bytes.
    std::uint64_t checkpoint_bytes = 32ull << 20;
  };

  struct Sweep {
    std::uint64_t offset = 0;       ///< uncompressed byte offset of the entry holding it
    std::size_t entry = 0;          ///< rawlog entry number (0-based)
    std::uint32_t in_entry = 0;     ///< position among the entry's observations
    std::int64_t timestamp_ns = 0;  ///< the observation's time
    std::optional<Eigen::Isometry3d> odometry;  ///< robot pose of the latest odometry before it
  };

  /// Indexes `rawlog` (gzip or plain). Throws RawlogError if it cannot be read to its end, has no
  /// LiDAR observation (with that label), mixes LiDAR labels without `sensor_label`, or its
  /// sweeps' times do not increase.
  RawlogIndex(std::string rawlog, ObservationConverter converter, Options opts);
  ~RawlogIndex();
  RawlogIndex(const RawlogIndex&) = delete;
  RawlogIndex& operator=(const RawlogIndex&) = delete;

  std::size_t size() const { return sweeps_.size(); }
  const Sweep& sweep(std::size_t k) const { return sweeps_.at(k); }
  const std::string& path() const { return path_; }
  const std::string& sensorLabel() const { return label_; }
  std::size_t entries() const { return entries_; }
  /// Decompressor states kept (gzip; 0 for a plain rawlog).
  std::size_t checkpoints() const;

  /// Reads and converts sweep k (index, entry, mount, odometry, observation filled in).
  /// Throws RawlogError / ConversionError naming the file and entry.
  void read(std::size_t k, Frame& f);

 private:
  class Stream;
  std::string path_;
  ObservationConverter converter_;
  std::unique_ptr<Stream> in_;
  std::vector<Sweep> sweeps_;
  std::string label_;
  std::size_t entries_ = 0;
};

}  // namespace dynobj::mrptio
