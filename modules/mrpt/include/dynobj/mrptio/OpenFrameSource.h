// SPDX-License-Identifier: BSD-3-Clause
// The frames of what a user names as input: a folder of point-cloud sweeps
// (CloudFolderFrameSource) or a rawlog (RawlogFrameSource).
#pragma once

#include <dynobj/core/SensorModel.h>

#include <memory>
#include <optional>
#include <string>

#include "dynobj/mrptio/FrameSource.h"

namespace dynobj::mrptio {

struct OpenedFrameSource {
  std::unique_ptr<FrameSource> source;
  std::size_t frames = 0;  ///< sweeps it holds when known beforehand (a folder), else 0
};

/// `sensor`: a preset for clouds without their own geometry (rows hint for a folder);
/// `sensor_label`: a rawlog's LiDAR to read (a folder's frames get this label, "LIDAR" when
/// empty). Throws std::runtime_error naming an input that does not exist, or the readers' errors.
OpenedFrameSource openFrameSource(const std::string& input,
                                  const std::optional<core::SensorModel>& sensor,
                                  const std::string& sensor_label);

}  // namespace dynobj::mrptio
