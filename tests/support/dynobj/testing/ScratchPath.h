// SPDX-License-Identifier: BSD-3-Clause
// A fresh path in the test program's scratch folder (its TMPDIR, set and removed by
// ScratchTestMain.cpp): "<TMPDIR>/scratch-<n><suffix>", n counting up, so two calls never give the
// same path. Nothing is created.
#pragma once

#include <atomic>
#include <filesystem>
#include <string>

namespace dynobj::testing {

inline std::string scratchPath(const std::string& suffix) {
  static std::atomic<int> n{0};
  return (std::filesystem::temp_directory_path() / ("scratch-" + std::to_string(n++) + suffix))
      .string();
}

}  // namespace dynobj::testing
