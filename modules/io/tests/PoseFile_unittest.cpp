// SPDX-License-Identifier: BSD-3-Clause
// readPoseFile: KITTI 3x4 and TUM files, auto-detected; malformed lines named by path:line.
#include <dynobj/io/PoseFile.h>
#include <gtest/gtest.h>

#include <fstream>

namespace io = dynobj::io;

namespace {

std::string write(const std::string& name, const std::string& text) {
  const std::string p = ::testing::TempDir() + "dynobj-io-pose-" + name;
  std::ofstream(p) << text;
  return p;
}

void expectError(const std::string& text, const std::string& what) {
  const std::string p = write("bad.txt", text);
  try {
    io::readPoseFile(p);
    ADD_FAILURE() << "no error for: " << what;
  } catch (const io::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(p + ":" + what), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(PoseFile, KittiRowsWithoutTimestamps) {
  const auto p = io::readPoseFile(
      write("kitti.txt", "# poses\n1 0 0 0 0 1 0 0 0 0 1 0\n\n0 -1 0 1.5 1 0 0 -2 0 0 1 0.25\n"));
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].timestamp_ns, -1);
  EXPECT_TRUE(p[0].pose.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_TRUE(p[1].pose.translation().isApprox(Eigen::Vector3d(1.5, -2, 0.25)));
  EXPECT_TRUE(p[1].pose.linear().isApprox(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix()));
}

TEST(PoseFile, TumWithExactNanosecondStamps) {
  const auto p =
      io::readPoseFile(write("tum.txt",
                             "# t tx ty tz qx qy qz qw\n1317354879.123456789 1 2 3 0 0 0 1\n"
                             "1317354879.2 0 0 0 0 0 0.7071068 0.7071068\n1.5e9 0 0 0 0 0 0 -1\n"));
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].timestamp_ns, 1317354879123456789);
  EXPECT_EQ(p[1].timestamp_ns, 1317354879200000000);
  EXPECT_EQ(p[2].timestamp_ns, 1500000000000000000);
  EXPECT_TRUE(p[0].pose.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(p[1].pose.linear().isApprox(
      Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix(), 1e-6));
  EXPECT_EQ(io::parseSecondsNs("-0.5"), -500000000);
  EXPECT_EQ(io::parseSecondsNs("1.036602e-01"), 103660200);
  EXPECT_FALSE(io::parseSecondsNs("12:00").has_value());
}

TEST(PoseFile, MalformedLinesNamePathAndLine) {
  const std::string kitti = "1 0 0 0 0 1 0 0 0 0 1 0\n";
  expectError(kitti + "1 2 3 0 0 0 1 0\n", "2: expected 12 numbers (KITTI 3x4 file), found 8");
  expectError("0 0 0 0 0 0 1\n", "1: expected 12 numbers (KITTI 3x4) or 8 (TUM");
  expectError(kitti + "1 0 0 0 0 1 0 0 0 0 1 zero\n", "2: 'zero' is not a number");
  expectError("1 0 0 0 0 2 0 0 0 0 1 0\n", "1: the 3x3 part is not a rotation");
  expectError("-1 0 0 0 0 1 0 0 0 0 1 0\n", "1: the 3x3 part is not a rotation");  // det -1
  expectError("0.1 0 0 0 0 0 0 0.9\n", "1: quaternion is not unit length");
  expectError("0.1 0 0 0 0 0 0 1\n0.1 0 0 0 0 0 0 1\n", "2: time stamp 0.1 is not after");
  expectError("1O.5 0 0 0 0 0 0 1\n", "1: '1O.5' is not a time stamp in seconds");
  EXPECT_THROW(io::readPoseFile(write("empty.txt", "# nothing\n")), io::FormatError);
  EXPECT_THROW(io::readPoseFile(write("tum2.txt", kitti), io::PoseFormat::Tum), io::FormatError);
}
