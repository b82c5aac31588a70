// SPDX-License-Identifier: BSD-3-Clause
// LZF decompression. The stream is a sequence of commands, each starting with a control byte c:
//   c < 32:  a literal run, the next c + 1 input bytes are copied to the output;
//   c >= 32: a back-reference of length L = (c >> 5) (+ the next byte when L == 7) plus 2, at
//            distance D = ((c & 31) << 8) + the next byte + 1 behind the current output end;
//            the copy may overlap its own output (runs).
#include "Lzf.h"

namespace dynobj::io::detail {

std::string lzfDecompress(const std::uint8_t* in, std::size_t in_size, std::uint8_t* out,
                          std::size_t out_size) {
  std::size_t ip = 0, op = 0;
  const auto at = [](std::size_t pos) {
    return " (at compressed byte " + std::to_string(pos) + ")";
  };
  while (ip < in_size) {
    const std::size_t command = ip;
    const unsigned ctrl = in[ip++];
    if (ctrl < 32) {
      const std::size_t len = ctrl + 1;
      if (len > in_size - ip) return "LZF data ends inside a literal run" + at(command);
      if (len > out_size - op)
        return "LZF output exceeds the declared " + std::to_string(out_size) + " bytes" +
               at(command);
      for (std::size_t i = 0; i < len; i++) out[op++] = in[ip++];
      continue;
    }
    std::size_t len = ctrl >> 5;
    if (len == 7) {
      if (ip >= in_size) return "LZF data ends inside a back-reference" + at(command);
      len += in[ip++];
    }
    len += 2;
    if (ip >= in_size) return "LZF data ends inside a back-reference" + at(command);
    const std::size_t dist = ((static_cast<std::size_t>(ctrl & 31) << 8) | in[ip++]) + 1;
    if (dist > op)
      return "LZF back-reference before the start of the output (distance " + std::to_string(dist) +
             " at output byte " + std::to_string(op) + ")" + at(command);
    if (len > out_size - op)
      return "LZF output exceeds the declared " + std::to_string(out_size) + " bytes" + at(command);
    for (std::size_t i = 0; i < len; i++, op++) out[op] = out[op - dist];
  }
  if (op != out_size)
    return "LZF output is " + std::to_string(op) + " bytes, the header declares " +
           std::to_string(out_size);
  return "";
}

}  // namespace dynobj::io::detail
