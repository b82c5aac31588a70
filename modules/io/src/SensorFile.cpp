// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/SensorFile.h"

#include <dynobj/core/Config.h>

#include "dynobj/io/IniFile.h"

namespace dynobj::io {

using core::ParameterError;

core::SensorModel readSensorModel(const std::string& ini_path, const std::string& section) {
  IniFile ini(ini_path, "sensor file");
  if (!ini.config().sectionExists(section))
    throw ParameterError(ini_path + ": section [" + section + "] not found");
  ini.expect(section, core::SensorModel::iniKeys());
  ini.check();
  core::SensorModel m;
  try {
    m.loadFromConfigFile(ini.config(), section);
  } catch (const ParameterError& e) {
    throw ParameterError(ini_path + ": [" + section + "] " + e.what());
  }
  return m;
}

}  // namespace dynobj::io
