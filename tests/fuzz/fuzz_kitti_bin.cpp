// SPDX-License-Identifier: BSD-3-Clause
// KITTI Velodyne .bin sweeps (io::readKittiBin).
#include <dynobj/io/KittiBin.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    dynobj::io::readKittiBin(dynobj::fuzz::asFile(data, size, ".bin"));
  } catch (const std::exception&) {
  }
  return 0;
}
