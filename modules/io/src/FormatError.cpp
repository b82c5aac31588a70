// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/FormatError.h"

namespace dynobj::io {

void throwFormatError(const std::string& path, const std::string& problem) {
  throw FormatError(path + ": " + problem);
}

}  // namespace dynobj::io
