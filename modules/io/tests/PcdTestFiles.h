// SPDX-License-Identifier: BSD-3-Clause
// Test helpers shared by the PCD tests: temporary files, raw bytes, and the error check.
#pragma once

#include <dynobj/io/FormatError.h>
#include <dynobj/io/PcdFile.h>
#include <gtest/gtest.h>

#include <fstream>
#include <string>

namespace pcd_test {

inline std::string tmp(const std::string& name) {
  return ::testing::TempDir() + "dynobj-io-pcd-" + name;
}

inline std::string write(const std::string& name, const std::string& bytes) {
  const std::string p = tmp(name);
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

template <typename T>
std::string raw(T v) {
  return std::string(reinterpret_cast<const char*>(&v), sizeof(v));
}

/// readPcd(path) throws a FormatError naming the file and containing `what`.
inline void expectError(const std::string& path, const std::string& what) {
  try {
    dynobj::io::readPcd(path);
    ADD_FAILURE() << "no error for: " << what;
  } catch (const dynobj::io::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

}  // namespace pcd_test
