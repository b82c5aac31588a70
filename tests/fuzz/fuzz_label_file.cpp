// SPDX-License-Identifier: BSD-3-Clause
// Dynamic-label files v1 and their instance variant (io::LabelFile::read).
#include <dynobj/io/LabelFile.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const auto f = dynobj::io::LabelFile::read(dynobj::fuzz::asFile(data, size, ".labels"));
    std::size_t n = 0;
    for (const auto& s : f.sweeps) n += s.pixels.size();
    (void)n;
  } catch (const std::exception&) {  // a clear error is the expected outcome
  }
  return 0;
}
