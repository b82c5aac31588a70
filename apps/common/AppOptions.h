// SPDX-License-Identifier: BSD-3-Clause
// The options every app spells the same way, as MRPT's own apps do: -i input, -o output,
// -w overwrite, -c detector config (INI), -q quiet, --sensor preset INI, --sensor-label label.
// Here: the shared ones that need the libraries (AppMain.h has parsing and exit codes).
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/core/SensorModel.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/ObservationConverter.h>
#include <mrpt/config/CConfigFile.h>

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

#include "AppMain.h"

namespace dynobj::apps {

/// --sensor (preset INI, for point clouds and rotating scans) and --sensor-label.
class SensorArgs {
 public:
  explicit SensorArgs(TCLAP::CmdLine& cmd, bool with_label = true)
      : sensor_("", "sensor", "Sensor preset INI (point clouds, rotating scans)", false, "",
                "file.ini"),
        label_("", "sensor-label", "Only the LiDAR with this label", false, "", "label") {
    cmd.add(sensor_);
    if (with_label) cmd.add(label_);
  }
  std::optional<core::SensorModel> model() const {
    if (!sensor_.isSet()) return std::nullopt;
    return io::readSensorModel(sensor_.getValue());
  }
  mrptio::ObservationConverter converter() const { return mrptio::ObservationConverter(model()); }
  const std::string& label() const { return label_.getValue(); }
  bool labelSet() const { return label_.isSet(); }
  const std::string& sensorFile() const { return sensor_.getValue(); }

 private:
  mutable TCLAP::ValueArg<std::string> sensor_, label_;  // TCLAP's getters are not const
};

/// The detector's parameters from `ini` (defaults when empty), sections prefixed by `section`.
/// Throws when the file does not exist or a key is bad.
inline core::DetectorParams loadDetectorParams(const std::string& ini,
                                               const std::string& section = "") {
  core::DetectorParams p;
  if (ini.empty()) return p;
  if (!std::filesystem::exists(ini))
    throw std::runtime_error("config file '" + ini + "' does not exist");
  mrpt::config::CConfigFile cfg(ini);
  p.load(cfg, section);
  return p;
}

}  // namespace dynobj::apps
