// SPDX-License-Identifier: BSD-3-Clause
// The options every app spells the same way, as MRPT's own apps do: -i input, -o output,
// -w overwrite, -c detector config (INI), -q quiet, --sensor preset INI, --sensor-label label.
// Here: the shared ones that need the libraries (AppMain.h has parsing and exit codes).
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/core/SensorModel.h>
#include <dynobj/io/IniFile.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/ObservationConverter.h>

#include <filesystem>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

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

/// --threads for the tools that run the detector: its [pipeline] threads (1 = every stage on one
/// core, 2 = the ego-motion on a second thread; the same results either way).
class ThreadsArg {
 public:
  explicit ThreadsArg(TCLAP::CmdLine& cmd)
      : values_{1, 2},
        allowed_(values_),
        arg_("", "threads",
             "Threads of the detector: 1 = one core, 2 = the ego-motion on a second thread "
             "(default: the configuration's [pipeline] threads, 2); same results",
             false, 2, &allowed_) {
    cmd.add(arg_);
  }
  /// Sets p.pipeline.threads when --threads was given.
  void apply(core::DetectorParams& p) const {
    if (arg_.isSet()) p.pipeline.threads = arg_.getValue();
  }

 private:
  std::vector<int> values_;
  TCLAP::ValuesConstraint<int> allowed_;
  mutable TCLAP::ValueArg<int> arg_;  // TCLAP's getters are not const
};

/// The detector's parameters from an INI file (io::loadDetectorParams: strict, errors name the
/// file and line).
using io::loadDetectorParams;

}  // namespace dynobj::apps
