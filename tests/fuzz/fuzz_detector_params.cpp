// SPDX-License-Identifier: BSD-3-Clause
// INI parameter loading: the detector's parameters (core::DetectorParams::load + validate) and a
// sensor preset (io::readSensorModel), from the same text.
#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/io/SensorFile.h>
#include <mrpt/config/CConfigFileMemory.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text = dynobj::fuzz::asText(data, size);
  try {
    mrpt::config::CConfigFileMemory cfg(text);
    dynobj::core::DetectorParams p;
    p.load(cfg, "");
    p.validate();
  } catch (const std::exception&) {
  }
  try {
    dynobj::io::readSensorModel(dynobj::fuzz::asFile(data, size, ".ini"));
  } catch (const std::exception&) {
  }
  return 0;
}
