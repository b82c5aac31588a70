// SPDX-License-Identifier: BSD-3-Clause
// The scans to map, one at a time (memory stays flat): from an MRPT rawlog (LiDAR observations,
// with the latest odometry seen before each), or from a KTH DynamicMap benchmark folder
// (pcd/NNNNNN.pcd, points in the world, VIEWPOINT = sensor pose; re-projected into a LiDAR frame
// with a sensor model). Can be opened again (a second reader, or rewind()).
#pragma once

#include <dynobj/core/SensorModel.h>
#include <dynobj/mrptio/FrameSource.h>

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

namespace dynobj::mapclean {

/// A scan to map: SequenceRunner's frame (rawlog: the observation, its mount and the latest
/// odometry; PCD folder: the VIEWPOINT).
using Scan = mrptio::Frame;
/// Scans one at a time; rewind() for the next pass.
using ScanSource = mrptio::FrameSource;

struct ScanSourceOptions {
  std::string sensor_label;                 ///< rawlog: only this label (empty = every LiDAR one)
  std::optional<core::SensorModel> sensor;  ///< required for PCD folders and point clouds
};

/// "*.rawlog" (or any file MRPT reads as a rawlog) or a directory holding pcd/*.pcd. Anything
/// else is an error naming the input and the formats expected.
std::unique_ptr<ScanSource> openScanSource(const std::string& input, const ScanSourceOptions& opts);

/// The time of a source's first scan (read without converting where the source can); the source
/// is rewound. Throws when it holds no scan.
std::int64_t firstScanTime(ScanSource& source);

/// The scans of `source` from `begin_ns` (inclusive) to `end_ns` (exclusive): a chunk of a long
/// recording (dynobj-mapclean --chunk-from/--chunk-to). The scans before are passed over without
/// being converted where the source can (rawlogs); reading stops at the first scan at or after
/// `end_ns`.
class TimeWindowSource final : public ScanSource {
 public:
  TimeWindowSource(std::unique_ptr<ScanSource> source, std::int64_t begin_ns, std::int64_t end_ns);
  bool next(Scan& s) override;
  void rewind() override;
  std::string describe() const override { return source_->describe(); }
  std::string noFramesDetail() const override { return source_->noFramesDetail(); }
  double progress() const override { return source_->progress(); }
  /// True once the input itself ended (no scan at or after `end_ns` was met).
  bool reachedEnd() const { return reached_end_; }

 private:
  std::unique_ptr<ScanSource> source_;
  std::int64_t begin_ns_, end_ns_;
  bool reached_end_ = false, done_ = false;
};

}  // namespace dynobj::mapclean
