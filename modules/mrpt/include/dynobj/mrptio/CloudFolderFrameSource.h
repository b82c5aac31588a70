// SPDX-License-Identifier: BSD-3-Clause
// A folder of point-cloud sweeps (*.pcd or KITTI *.bin, io::CloudFolder) as LiDAR frames: the one
// conversion of a user's sweep files, shared by dynobj-import (which writes the frames as a
// rawlog) and the tools that read such a folder directly (dynobj-eval, dynobj-detect). Per sweep:
// points into the sensor frame (PCD VIEWPOINT), then core::SweepProjector (intensity on one
// scale for the whole recording, rows recovered as the first complete sweep found them), time
// stamps from a times file or the rate. Each frame keeps its
// input points (Frame::points), in the file's order, so that per-pixel results map back to every
// point of the file.
#pragma once

#include <dynobj/core/RowRecovery.h>
#include <dynobj/core/SweepProjector.h>
#include <dynobj/io/CloudFolder.h>

#include <map>
#include <optional>
#include <string>

#include "dynobj/mrptio/FrameSource.h"

namespace dynobj::mrptio {

struct CloudFolderOptions {
  std::string times;                        ///< times file (see io::CloudFolder); empty = `rate`
  double rate = 10.0;                       ///< [Hz] sweep rate without a times file
  std::optional<core::SensorModel> sensor;  ///< rows / columns hint (else recovered)
  std::string sensor_label = "LIDAR";
};

class CloudFolderFrameSource final : public FrameSource {
 public:
  /// Throws io::FormatError (no sweep, a bad times file), std::invalid_argument (rate <= 0).
  CloudFolderFrameSource(const std::string& dir, CloudFolderOptions o);

  bool next(Frame& f) override;
  void rewind() override;
  std::string describe() const override;

  const io::CloudFolder& folder() const { return folder_; }
  /// How the rows of the sweeps read so far were found: rule -> sweeps.
  const std::map<core::RowSource, std::size_t>& rowSources() const { return row_sources_; }
  /// Lasers found in the last sweep read (core::projectUnordered; 0 when the rows came from a
  /// table), for checking a preset against the data.
  int lastLasers() const { return projector_.lastLasers(); }
  /// The field that became the intensity and its scale ("'intensity' x 255"), after a sweep.
  const std::string& intensityDescription() const { return intensity_; }

 private:
  std::string dir_;
  CloudFolderOptions o_;
  io::CloudFolder folder_;
  std::size_t pos_ = 0;
  core::SweepProjector projector_;
  std::string intensity_;
  std::map<core::RowSource, std::size_t> row_sources_;
};

/// "firing order 153, estimated table 1": the rules of rowSources(), most used first.
std::string describeRowSources(const std::map<core::RowSource, std::size_t>& sources);

}  // namespace dynobj::mrptio
