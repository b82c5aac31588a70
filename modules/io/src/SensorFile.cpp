// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/SensorFile.h"

#include <dynobj/core/Config.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/system/filesystem.h>

namespace dynobj::io {

using core::ParameterError;

core::SensorModel readSensorModel(const std::string& ini_path, const std::string& section) {
  if (!mrpt::system::fileExists(ini_path))
    throw ParameterError("sensor file '" + ini_path + "' does not exist");
  mrpt::config::CConfigFile cfg(ini_path);
  if (!cfg.sectionExists(section))
    throw ParameterError(ini_path + ": section [" + section + "] not found");
  core::SensorModel m;
  try {
    m.loadFromConfigFile(cfg, section);
  } catch (const ParameterError& e) {
    throw ParameterError(ini_path + ": [" + section + "] " + e.what());
  }
  return m;
}

}  // namespace dynobj::io
