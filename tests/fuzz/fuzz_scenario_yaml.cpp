// SPDX-License-Identifier: BSD-3-Clause
// Scenario YAML (sim::Scenario::fromYamlText). `sensor:` paths resolve in the shipped share dir.
#include <dynobj/sim/Scenario.h>

#include "FuzzInput.h"

#ifndef DYNOBJ_SHARE_DIR
#define DYNOBJ_SHARE_DIR "share/dynobj"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    dynobj::sim::Scenario::fromYamlText(dynobj::fuzz::asText(data, size), DYNOBJ_SHARE_DIR);
  } catch (const std::exception&) {
  }
  return 0;
}
