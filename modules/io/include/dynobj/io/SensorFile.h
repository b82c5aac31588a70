// SPDX-License-Identifier: BSD-3-Clause
// Sensor presets as files: share/dynobj/sensors/*.ini (the keys: core/SensorModel.h).
#pragma once

#include <dynobj/core/SensorModel.h>

#include <string>

namespace dynobj::io {

/// Loads and validates `section` of an INI file; throws core::ParameterError naming the file and
/// the key, also for a key or section a preset does not have (io::IniFile).
core::SensorModel readSensorModel(const std::string& ini_path,
                                  const std::string& section = "sensor");

}  // namespace dynobj::io
