// SPDX-License-Identifier: BSD-3-Clause
// The one error type of every reader in dynobj::io: a file that is missing, truncated, malformed
// or of an unsupported variant. what() = "<path>: <problem>" (or "<path>:<line>: <problem>").
#pragma once

#include <stdexcept>
#include <string>

namespace dynobj::io {

class FormatError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Throws FormatError("<path>: <problem>").
[[noreturn]] void throwFormatError(const std::string& path, const std::string& problem);

}  // namespace dynobj::io
