// SPDX-License-Identifier: BSD-3-Clause
// Shared by the libFuzzer harnesses: the parsers under test read files by name, so each input is
// written to one temporary file per process (in /dev/shm when there is one) first.
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

namespace dynobj::fuzz {

inline std::string tempPath(const std::string& suffix) {
  const std::string dir = std::filesystem::is_directory("/dev/shm") ? "/dev/shm" : "/tmp";
  return dir + "/dynobj-fuzz-" + std::to_string(::getpid()) + suffix;
}

/// Writes the input to this process's temporary file with `suffix`; returns its path.
inline const std::string& asFile(const std::uint8_t* data, std::size_t size,
                                 const std::string& suffix) {
  static const std::string path = tempPath(suffix);
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

inline std::string asText(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

}  // namespace dynobj::fuzz
