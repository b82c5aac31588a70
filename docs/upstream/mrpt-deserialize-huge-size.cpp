// SPDX-License-Identifier: BSD-3-Clause
// Standalone reproducer for an MRPT 2.5.x deserialization crash (report upstream; see README.md):
// a CObservation3DRangeScan whose serialized range-image size is damaged makes
// CArchive::ReadObject() die of SIGSEGV instead of throwing.
//
//   g++ -std=c++17 mrpt-deserialize-huge-size.cpp -o repro \
//     $(for m in core io obs serialization; do echo -I/usr/include/mrpt/$m/include; done) ...
// or with the CMakeLists.txt next to this file:
//   cmake -S . -B build && cmake --build build && ./build/repro
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdint>
#include <cstring>
#include <iostream>
#include <vector>

int main() {
  // 1. A small, valid observation: a 3 x 5 range image, nothing else.
  mrpt::obs::CObservation3DRangeScan obs;
  obs.hasRangeImage = true;
  obs.rangeImage_setSize(3, 5);
  obs.rangeImage.fill(1000);
  mrpt::io::CMemoryStream buf;
  mrpt::serialization::archiveFrom(buf) << obs;
  std::vector<uint8_t> bytes(buf.getTotalBytesCount());
  std::memcpy(bytes.data(), buf.getRawBufferData(), bytes.size());

  // 2. Damage one field, as a flipped bit or a bad sector would: the range image's size
  //    (serialized as uint32 rows, uint32 cols right before the pixels).
  const uint8_t rows_cols[8] = {3, 0, 0, 0, 5, 0, 0, 0};
  bool patched = false;
  for (size_t i = 0; i + 8 <= bytes.size() && !patched; i++)
    if (std::memcmp(&bytes[i], rows_cols, 8) == 0) {
      // 1,000,000 x 100,000 pixels: 200 GB, more than any machine can give
      const uint32_t rows = 1000000u, cols = 100000u;
      std::memcpy(&bytes[i], &rows, 4);
      std::memcpy(&bytes[i + 4], &cols, 4);
      patched = true;
    }
  if (!patched) {
    std::cerr << "could not find the range image size in the serialized bytes\n";
    return 2;
  }

  // 3. Read it back. Expected: an exception ("corrupt stream" / std::bad_alloc).
  //    MRPT 2.5.8: SIGSEGV in memset, from std::vector<uint16_t, aligned_allocator_cpp11>::
  //    _M_default_append <- CMatrixDynamic<uint16_t>::realloc <- rangeImage_setSize <-
  //    CObservation3DRangeScan::serializeFrom: mrpt::aligned_malloc() returns nullptr for the
  //    impossible size and aligned_allocator_cpp11::allocate() passes it on instead of throwing.
  mrpt::io::CMemoryStream in;
  in.assignMemoryNotOwn(bytes.data(), bytes.size());
  try {
    auto obj = mrpt::serialization::archiveFrom(in).ReadObject();
    std::cout << "read back without error (not expected either)\n";
  } catch (const std::exception& e) {
    std::cout << "OK: an exception, as expected: " << std::string(e.what()).substr(0, 200) << "\n";
    return 0;
  }
  return 1;
}
