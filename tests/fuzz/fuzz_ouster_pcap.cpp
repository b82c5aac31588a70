// SPDX-License-Identifier: BSD-3-Clause
// Ouster pcap captures (io::PcapReader + io::OusterPcapReader) with a fixed metadata file: the
// committed tests/fuzz/ouster_pcap.json (4 x 16 sensor, RNG19 profile, as in Ouster_unittest).
#include <dynobj/io/OusterMetadata.h>
#include <dynobj/io/OusterPcapReader.h>

#include "FuzzInput.h"

#ifndef DYNOBJ_FUZZ_DIR
#define DYNOBJ_FUZZ_DIR "tests/fuzz"
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const auto meta =
      dynobj::io::OusterMetadata::load(std::string(DYNOBJ_FUZZ_DIR) + "/ouster_pcap.json");
  try {
    dynobj::io::OusterPcapReader reader(dynobj::fuzz::asFile(data, size, ".pcap"), meta);
    dynobj::io::OusterScan scan;
    for (int i = 0; i < 64 && reader.next(scan); i++) {
    }
  } catch (const std::exception&) {
  }
  return 0;
}
