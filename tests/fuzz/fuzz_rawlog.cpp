// SPDX-License-Identifier: BSD-3-Clause
// The rawlog reader (mrptio::RawlogReader: the serialized-object check, then MRPT's
// deserializers) on an in-memory (uncompressed)
// rawlog. Seeds: small rawlogs in the sample's format (tests/fuzz/rawlog/).
#include <dynobj/mrptio/RawlogReader.h>
#include <mrpt/io/CMemoryStream.h>

#include "FuzzInput.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  auto mem = std::make_unique<mrpt::io::CMemoryStream>();
  mem->assignMemoryNotOwn(data, size);
  try {
    dynobj::mrptio::RawlogReader reader(std::move(mem), "fuzz.rawlog");
    dynobj::mrptio::RawlogEntry e;
    while (reader.next(e)) {
    }
  } catch (const std::exception&) {
  }
  return 0;
}
