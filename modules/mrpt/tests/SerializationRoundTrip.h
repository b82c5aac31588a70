// SPDX-License-Identifier: BSD-3-Clause
// Test helper: an MRPT object written to memory and read back, as a rawlog would carry it.
#pragma once

#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

namespace dynobj::test {

template <class T>
typename T::Ptr serializeRoundTrip(const T& o) {
  mrpt::io::CMemoryStream buf;
  auto out = mrpt::serialization::archiveFrom(buf);
  out << o;
  buf.Seek(0);
  auto in = mrpt::serialization::archiveFrom(buf);
  return in.ReadObject<T>();
}

}  // namespace dynobj::test
