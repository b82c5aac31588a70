// SPDX-License-Identifier: BSD-3-Clause
// Ouster metadata JSON (io::OusterMetadata::parse).
#include <dynobj/io/OusterMetadata.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    dynobj::io::OusterMetadata::parse(dynobj::fuzz::asText(data, size), "fuzz.json");
  } catch (const std::exception&) {
  }
  return 0;
}
