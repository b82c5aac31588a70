// SPDX-License-Identifier: BSD-3-Clause
// The PCD header (private to dynobj::io): field layout, point counts, DATA layout, parsed and
// checked by parseHeader; readScalar decodes one stored value of a field.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynobj/io/CloudFile.h"

namespace dynobj::io::detail {

struct PcdField {
  std::string name;
  std::size_t size = 0, count = 1;
  char type = 0;           ///< 'F', 'U' or 'I'
  std::size_t offset = 0;  ///< bytes from the start of a binary record
  std::size_t value = 0;   ///< index of its first value on an ascii line
};

struct PcdHeader {
  std::vector<PcdField> fields;
  std::size_t width = 0, height = 1, points = 0;
  std::string data;            ///< ascii, binary or binary_compressed
  std::size_t data_begin = 0;  ///< byte offset of the data section in the file
  std::size_t data_line = 0;   ///< line number of the first data line
  std::size_t record = 0;      ///< bytes per point
  std::size_t values = 0;      ///< values per point (sum of COUNT)
};

/// Parses the header at the start of `buf` (the whole file); fills out.viewpoint, out.comments.
/// Checks field types and sizes, POINTS = WIDTH x HEIGHT. Throws FormatError.
PcdHeader parsePcdHeader(const std::string& path, const std::string& buf, CloudFile& out);

/// The value of field `f` stored at `p` (little-endian).
double readScalar(const std::uint8_t* p, const PcdField& f);

/// Throws FormatError "<path>:<line>: <problem>".
[[noreturn]] void failAt(const std::string& path, std::size_t line, const std::string& problem);

}  // namespace dynobj::io::detail
