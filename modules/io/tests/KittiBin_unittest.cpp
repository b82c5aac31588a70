// SPDX-License-Identifier: BSD-3-Clause
// readKittiBin on hand-made files: exact values, NaN points dropped, sizes not a multiple of 16.
#include <dynobj/io/KittiBin.h>
#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <vector>

namespace io = dynobj::io;

namespace {

std::string write(const std::string& name, const std::vector<float>& v, std::size_t extra = 0) {
  const std::string p = ::testing::TempDir() + "dynobj-io-kitti-" + name;
  std::ofstream out(p, std::ios::binary);
  out.write(reinterpret_cast<const char*>(v.data()), static_cast<std::streamsize>(4 * v.size()));
  out << std::string(extra, '\0');
  return p;
}

}  // namespace

TEST(KittiBin, ReadsRecordsAndDropsNan) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const auto c = io::readKittiBin(write("a.bin", {1, 2, 3, 0.5f, nan, 0, 0, 0.1f, -4, 5, -6, 0.f}));
  EXPECT_EQ(c.cloud.x, (std::vector<float>{1, -4}));
  EXPECT_EQ(c.cloud.y, (std::vector<float>{2, 5}));
  EXPECT_EQ(c.cloud.z, (std::vector<float>{3, -6}));
  EXPECT_EQ(c.cloud.intensity, (std::vector<float>{0.5f, 0}));
  EXPECT_EQ(c.dropped_nonfinite, 1u);
  EXPECT_EQ(c.intensity_field, "intensity");
  EXPECT_TRUE(c.time_s.empty());
  EXPECT_TRUE(c.viewpoint.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_TRUE(io::readKittiBin(write("empty.bin", {})).cloud.empty());
}

TEST(KittiBin, SizeNotAMultipleOf16IsAnError) {
  const std::string p = write("17.bin", {1, 2, 3, 4}, 1);
  try {
    io::readKittiBin(p);
    FAIL() << "no error";
  } catch (const io::FormatError& e) {
    EXPECT_EQ(std::string(e.what()),
              p + ": size 17 bytes is not a multiple of 16 (float32 x y z intensity records)");
  }
  EXPECT_THROW(io::readKittiBin(p + ".missing"), io::FormatError);
}
