// SPDX-License-Identifier: BSD-3-Clause
// PCD files: ascii, binary, binary_compressed (io::readPcd, with its LZF decoder).
#include <dynobj/io/PcdFile.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    dynobj::io::readPcd(dynobj::fuzz::asFile(data, size, ".pcd"));
  } catch (const std::exception&) {
  }
  return 0;
}
