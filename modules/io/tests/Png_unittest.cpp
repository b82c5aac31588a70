// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/Png.h>
#include <gtest/gtest.h>

#include <filesystem>

using namespace dynobj::io;

TEST(Png, UnwritablePathThrowsNamingIt) {
  cv::Mat_<std::uint8_t> img(2, 2, std::uint8_t{7});
  try {
    writePng("/nonexistent-dir/x.png", img);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/x.png"), std::string::npos);
  }
}

TEST(Png, AtomicWriteLeavesOnlyTheFinalFile) {
  const std::string p = (std::filesystem::temp_directory_path() / "dynobj_png_atomic.png").string();
  writePngAtomically(p, cv::Mat_<std::uint8_t>(2, 2, std::uint8_t{7}));
  EXPECT_TRUE(std::filesystem::exists(p));
  EXPECT_FALSE(std::filesystem::exists(p + ".partial.png"));
  std::filesystem::remove(p);
}
