// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/OpenFrameSource.h"

#include <filesystem>
#include <stdexcept>

#include "dynobj/mrptio/CloudFolderFrameSource.h"
#include "dynobj/mrptio/RawlogFrameSource.h"

namespace dynobj::mrptio {

OpenedFrameSource openFrameSource(const std::string& input,
                                  const std::optional<core::SensorModel>& sensor,
                                  const std::string& sensor_label) {
  namespace fs = std::filesystem;
  OpenedFrameSource out;
  if (fs::is_directory(input)) {
    auto folder = std::make_unique<CloudFolderFrameSource>(
        input, CloudFolderOptions{"", 10.0, sensor, sensor_label.empty() ? "LIDAR" : sensor_label});
    out.frames = folder->folder().size();
    out.source = std::move(folder);
    return out;
  }
  if (!fs::exists(input)) throw std::runtime_error("input '" + input + "' does not exist");
  out.source = std::make_unique<RawlogFrameSource>(input, ObservationConverter(sensor),
                                                   RawlogFrameSource::Options{sensor_label});
  return out;
}

}  // namespace dynobj::mrptio
