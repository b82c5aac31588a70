// SPDX-License-Identifier: BSD-3-Clause
// LZF decompression (the compression of PCD's DATA binary_compressed): private to dynobj::io.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace dynobj::io::detail {

/// Decompresses `in` into exactly `out_size` bytes at `out`. Returns "" on success, else the
/// problem (a back-reference before the start of the output, input ending inside a command,
/// output longer or shorter than out_size). Never reads or writes out of bounds.
std::string lzfDecompress(const std::uint8_t* in, std::size_t in_size, std::uint8_t* out,
                          std::size_t out_size);

}  // namespace dynobj::io::detail
