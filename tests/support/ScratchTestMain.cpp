// SPDX-License-Identifier: BSD-3-Clause
// The main() of every GoogleTest program of the project (instead of gtest_main): the process gets
// a scratch folder of its own, $TMPDIR/dynobj-test-<pid>, made its TMPDIR and TEST_TMPDIR (so that
// ::testing::TempDir() and std::filesystem::temp_directory_path() point into it), and removed with
// everything in it when the tests are over, whatever they wrote: no test leaves files behind.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <system_error>

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  const fs::path scratch = fs::temp_directory_path() / ("dynobj-test-" + std::to_string(getpid()));
  std::error_code ec;
  fs::remove_all(scratch, ec);
  fs::create_directories(scratch, ec);
  if (ec) {
    std::cerr << "cannot create the tests' scratch folder '" << scratch.string()
              << "': " << ec.message() << "\n";
    return 2;
  }
  setenv("TMPDIR", scratch.c_str(), 1);
  setenv("TEST_TMPDIR", scratch.c_str(), 1);  // read first by ::testing::TempDir()
  ::testing::InitGoogleTest(&argc, argv);
  const int rc = RUN_ALL_TESTS();
  fs::remove_all(scratch, ec);
  if (ec) {
    std::cerr << "cannot remove the tests' scratch folder '" << scratch.string()
              << "': " << ec.message() << "\n";
    return rc ? rc : 3;
  }
  return rc;
}
