// SPDX-License-Identifier: BSD-3-Clause
// readPcd / PcdWriter on tiny hand-made files: ascii and binary layouts, every field type, ring and
// time fields, organized clouds, padding, malformed files naming their problem (binary_compressed:
// PcdLzf_unittest.cpp).
#include <dynobj/io/PcdFile.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "PcdTestFiles.h"

namespace io = dynobj::io;
using pcd_test::expectError;
using pcd_test::raw;
using pcd_test::tmp;
using pcd_test::write;

namespace {

const std::string kXyz = "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

}  // namespace

TEST(PcdFile, AsciiWithRingTimeNanAndComments) {
  const auto c = io::readPcd(write(
      "ascii.pcd",
      "# .PCD v0.7 - Point Cloud Data file format\n# recorded by hand\nVERSION 0.7\n"
      "FIELDS x y z intensity ring time\nSIZE 8 4 4 2 2 4\nTYPE F F F U U F\nCOUNT 1 1 1 1 1 1\n"
      "WIDTH 3\nHEIGHT 1\nVIEWPOINT 1 2 3 0 0 0 1\nPOINTS 3\nDATA ascii\n"
      "0.5 -1 2e1 700 63 -0.05\n\nnan 0 0 1 1 0\n+3 4 5 0 0 0.025\n"));
  ASSERT_EQ(c.cloud.size(), 2u);
  c.cloud.validate();
  EXPECT_EQ(c.dropped_nonfinite, 1u);
  EXPECT_EQ(c.cloud.x, (std::vector<float>{0.5f, 3}));
  EXPECT_EQ(c.cloud.z, (std::vector<float>{20, 5}));
  EXPECT_EQ(c.cloud.intensity, (std::vector<float>{700, 0}));
  EXPECT_EQ(c.cloud.ring, (std::vector<std::uint16_t>{63, 0}));
  EXPECT_EQ(c.time_s, (std::vector<float>{-0.05f, 0.025f}));  // float seconds, kept as stored
  EXPECT_EQ(c.intensity_field, "intensity");
  EXPECT_EQ(c.time_field, "time");
  EXPECT_EQ(c.comments, std::vector<std::string>{"recorded by hand"});
  EXPECT_TRUE(c.viewpoint.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(
      c.viewpoint.linear().isApprox(Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()));
}

TEST(PcdFile, BinaryReadsEveryFieldTypeAndSkipsTheRest) {
  // x F4, y F8, z I2, i U1, ring U2, t U4 (ns); skipped: a I1, b I4, hist U2 x3, c U8, d I8.
  const std::string head =
      "VERSION .7\nFIELDS x a y z b i hist ring c t d\nSIZE 4 1 8 2 4 1 2 2 8 4 8\n"
      "TYPE F I F I I U U U U U I\nCOUNT 1 1 1 1 1 1 3 1 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n"
      "DATA binary\n";
  std::string data;
  for (int k = 0; k < 2; k++)
    data += raw(1.5f + k) + raw<std::int8_t>(-7) + raw(-2.25 * (k + 1)) +
            raw<std::int16_t>(static_cast<std::int16_t>(-300 + k)) + raw<std::int32_t>(-1) +
            raw<std::uint8_t>(static_cast<std::uint8_t>(200 + k)) + std::string(6, '\x7f') +
            raw<std::uint16_t>(static_cast<std::uint16_t>(127 - k)) + raw<std::uint64_t>(~0ull) +
            raw<std::uint32_t>(50000000u * k) + raw<std::int64_t>(-5);
  const auto c = io::readPcd(write("types.pcd", head + data + std::string(100, '\0')));
  ASSERT_EQ(c.cloud.size(), 2u);
  EXPECT_EQ(c.cloud.x, (std::vector<float>{1.5f, 2.5f}));
  EXPECT_EQ(c.cloud.y, (std::vector<float>{-2.25f, -4.5f}));
  EXPECT_EQ(c.cloud.z, (std::vector<float>{-300, -299}));
  EXPECT_EQ(c.cloud.intensity, (std::vector<float>{200, 201}));
  EXPECT_EQ(c.intensity_field, "i");
  EXPECT_EQ(c.cloud.ring, (std::vector<std::uint16_t>{127, 126}));
  EXPECT_EQ(c.time_field, "t");
  EXPECT_EQ(c.time_s, (std::vector<float>{0.f, 0.05f}));  // integer t = nanoseconds
  EXPECT_EQ(c.time_origin_ns, 0);
  EXPECT_EQ(c.width, 2u);
}

TEST(PcdFile, IntensityFieldPreferenceAndAbsoluteTimestamps) {
  const std::string head =
      "FIELDS reflectivity x y z timestamp\nSIZE 2 4 4 4 8\nTYPE U F F F F\nWIDTH 2\nPOINTS 2\n";
  const std::string data = raw<std::uint16_t>(9) + raw(1.f) + raw(2.f) + raw(3.f) +
                           raw(1700000000.25) + raw<std::uint16_t>(8) + raw(4.f) + raw(5.f) +
                           raw(6.f) + raw(1700000000.125);
  const auto c = io::readPcd(write("refl.pcd", head + "DATA binary\n" + data));
  EXPECT_EQ(c.intensity_field, "reflectivity");
  EXPECT_EQ(c.cloud.intensity, (std::vector<float>{9, 8}));
  EXPECT_LT(std::llabs(c.time_origin_ns - 1700000000125000000), 1000);  // epoch: from the earliest
  EXPECT_EQ(c.time_s, (std::vector<float>{0.125f, 0.f}));
  const auto both =
      io::readPcd(write("both.pcd",
                        "FIELDS x y z reflectivity intensity\nSIZE 4 4 4 4 4\nTYPE F F F F F\n"
                        "POINTS 1\nDATA ascii\n1 2 3 4 5\n"));
  EXPECT_EQ(both.intensity_field, "intensity");
  EXPECT_EQ(both.cloud.intensity, std::vector<float>{5});
  const auto none = io::readPcd(write("none.pcd",
                                      "COLUMNS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                      "POINTS 1\nDATA ascii\n1 2 3\n"));  // v0.5 style
  EXPECT_EQ(none.intensity_field, "");
  EXPECT_FALSE(none.cloud.hasIntensity());
  EXPECT_TRUE(none.time_s.empty());
  EXPECT_FALSE(none.cloud.hasRing());
}

TEST(PcdFile, OrganizedKeepsStoredOrderAndDropsNan) {
  std::string data;
  for (int k = 0; k < 6; k++)
    data += raw(k == 4 ? kNan : static_cast<float>(k)) + raw(0.f) + raw(1.f);
  const auto c =
      io::readPcd(write("org.pcd", kXyz + "WIDTH 3\nHEIGHT 2\nPOINTS 6\nDATA binary\n" + data));
  EXPECT_EQ(c.width, 3u);
  EXPECT_EQ(c.height, 2u);
  EXPECT_EQ(c.dropped_nonfinite, 1u);
  EXPECT_EQ(c.cloud.x, (std::vector<float>{0, 1, 2, 3, 5}));
  EXPECT_FALSE(c.cloud.isOrganized());  // no beam/azimuth meaning is assumed for the grid
}

TEST(PcdFile, MalformedFilesNameTheProblem) {
  const std::string p = tmp("bad.pcd");
  const auto bad = [&](const std::string& text, const std::string& what) {
    write("bad.pcd", text);
    expectError(p, what);
  };
  const std::string two = "WIDTH 2\nHEIGHT 1\nPOINTS 2\n";
  bad(kXyz + two + "DATA binary\n" + std::string(23, '\0'),
      "binary data is truncated: POINTS 2 need 24 bytes, 23 follow the header");
  bad("FIELDS x y\nSIZE 4 4\nTYPE F F\nPOINTS 0\nDATA ascii\n", "no field 'z'");
  bad("FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 2 1\nPOINTS 0\nDATA ascii\n", "no field 'y'");
  bad("FIELDS x y z\nSIZE 4 2 4\nTYPE F F F\nPOINTS 0\nDATA ascii\n",
      "field 'y': unsupported TYPE F with SIZE 2");
  bad("FIELDS x y z\nSIZE 4 4 4\nTYPE F X F\nPOINTS 0\nDATA ascii\n",
      "field 'y': unsupported TYPE X with SIZE 4");
  bad(kXyz + "WIDTH 2\nHEIGHT 2\nPOINTS 3\nDATA ascii\n", "POINTS 3 != WIDTH 2 x HEIGHT 2");
  bad(kXyz + two + "DATA ascii\n1 2 3\n4 five 6\n", p + ":10: 'five' is not a number");
  bad(kXyz + two + "DATA ascii\n1 2 3\n4 5\n", p + ":10: expected 3 values, found 2");
  bad(kXyz + two + "DATA ascii\n1 2 3\n", "ascii data is truncated: 1 of POINTS 2 points");
  bad(kXyz + two + "DATA binary_packed\n", "unsupported DATA binary_packed");
  bad(kXyz + two, "no DATA line");
  bad("hello world\n", p + ":1: not a PCD header line");
  bad(kXyz + "VIEWPOINT 0 0 0 2 0 0 0\nPOINTS 0\nDATA ascii\n", "quaternion is not unit length");
  bad(kXyz + "WIDTH -3\n", p + ":5: bad WIDTH value '-3'");
  bad("FIELDS x y z ring\nSIZE 4 4 4 4\nTYPE F F F F\nPOINTS 1\nDATA ascii\n1 2 3 2.5\n",
      "ring 2.5");
  EXPECT_THROW(io::readPcd(tmp("missing.pcd")), io::FormatError);
}

TEST(PcdFile, WriterRoundTripAndStreaming) {
  dynobj::core::PointCloud cloud;
  cloud.push_back(1, 2, 3, 4);
  cloud.push_back(-1.5f, 0.25f, 9, 255);
  Eigen::Isometry3d vp = Eigen::Isometry3d::Identity();
  vp.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 0.3, 1).normalized()).matrix();
  vp.translation() = Eigen::Vector3d(-15.65, 17.98, -0.93);
  const std::string p = tmp("rt.pcd");
  io::writePcd(p, cloud, vp, "timestamp_ns 42");
  const auto c = io::readPcd(p);
  EXPECT_EQ(c.cloud.x, cloud.x);
  EXPECT_EQ(c.cloud.y, cloud.y);
  EXPECT_EQ(c.cloud.z, cloud.z);
  EXPECT_EQ(c.cloud.intensity, cloud.intensity);
  EXPECT_TRUE(c.viewpoint.isApprox(vp, 1e-7));
  EXPECT_EQ(c.comments, std::vector<std::string>{"timestamp_ns 42"});

  const std::string s = tmp("stream.pcd");
  {
    io::PcdWriter w(s);
    for (int k = 0; k < 1000; k++) w.add(static_cast<float>(k), 0, 0, 1);
    w.close();
  }
  const auto st = io::readPcd(s);
  ASSERT_EQ(st.cloud.size(), 1000u);
  EXPECT_EQ(st.cloud.x.back(), 999.f);
  io::PcdWriter w(tmp("short.pcd"), Eigen::Isometry3d::Identity(), "", 3);
  w.add(1, 2, 3, 4);
  EXPECT_THROW(w.close(), io::FormatError);
}
