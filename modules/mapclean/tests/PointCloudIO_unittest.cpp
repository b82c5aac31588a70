// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/PointCloudIO.h>
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "FrameFixture.h"

namespace mc = dynobj::mapclean;
namespace fs = std::filesystem;

namespace {

std::string tmp(const std::string& name) {
  return dynobj::mapclean::test::tmpPath(name);
}

Eigen::Isometry3d somePose() {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.2, 0.3, 1).normalized()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(-15.65, 17.98, -0.93);
  return T;
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

}  // namespace

TEST(PointCloudIO, BinaryPcdRoundTripKeepsPointsViewpointAndComment) {
  const std::vector<mc::MapPoint> pts = {{1, 2, 3, 4}, {-1.5f, 0.25f, 9, 0}, {0, 0, 0, 255}};
  const std::string f = tmp("rt.pcd");
  mc::writePcd(f, pts, somePose(), "timestamp_ns 42");
  EXPECT_FALSE(fs::exists(f + ".partial"));
  const auto c = mc::readPcd(f);
  ASSERT_EQ(c.points.size(), 3u);
  EXPECT_TRUE(c.has_intensity);
  for (std::size_t i = 0; i < 3; i++) {
    EXPECT_EQ(c.points[i].x, pts[i].x);
    EXPECT_EQ(c.points[i].y, pts[i].y);
    EXPECT_EQ(c.points[i].z, pts[i].z);
    EXPECT_EQ(c.points[i].intensity, pts[i].intensity);
  }
  EXPECT_TRUE(c.viewpoint.isApprox(somePose(), 1e-7));
  ASSERT_EQ(c.comments.size(), 1u);
  EXPECT_EQ(c.comments[0], "timestamp_ns 42");
}

TEST(PointCloudIO, AsciiPcdWithOtherFieldsAndTypes) {
  const std::string f = tmp("ascii.pcd");
  writeText(
      f,
      "VERSION .7\nFIELDS x y z rgb intensity\nSIZE 8 8 8 4 1\nTYPE F F F U U\nCOUNT 1 1 1 1 1\n"
      "WIDTH 2\nHEIGHT 1\nVIEWPOINT 1 2 3 1 0 0 0\nPOINTS 2\nDATA ascii\n0.5 1 2 77 9\n3 4 5 0 "
      "200\n");
  const auto c = mc::readPcd(f);
  ASSERT_EQ(c.points.size(), 2u);
  EXPECT_FLOAT_EQ(c.points[0].x, 0.5f);
  EXPECT_FLOAT_EQ(c.points[0].intensity, 9.f);
  EXPECT_FLOAT_EQ(c.points[1].intensity, 200.f);
  EXPECT_TRUE(c.viewpoint.translation().isApprox(Eigen::Vector3d(1, 2, 3)));
}

TEST(PointCloudIO, StreamWriterPatchesTheCountAndMatchesWritePcd) {
  const std::string a = tmp("stream.pcd"), b = tmp("whole.pcd");
  fs::remove(a);
  std::vector<mc::MapPoint> pts;
  {
    mc::PcdStreamWriter w(a);
    for (int i = 0; i < 1234; i++) {
      pts.push_back({static_cast<float>(i), 0, 1, static_cast<float>(i % 2)});
      w.add(pts.back());
    }
    EXPECT_FALSE(fs::exists(a));  // not before close
    w.close();
  }
  mc::writePcd(b, pts);
  const auto ca = mc::readPcd(a), cb = mc::readPcd(b);
  ASSERT_EQ(ca.points.size(), 1234u);
  EXPECT_EQ(ca.points[1233].x, 1233.f);
  EXPECT_EQ(ca.points[1233].intensity, 1.f);
  EXPECT_EQ(fs::file_size(a) - fs::file_size(b),
            2u * 12u - 2u * 4u);  // padded counts (12 chars vs "1234")
}

TEST(PointCloudIO, UnclosedStreamWriterLeavesNothing) {
  const std::string a = tmp("abandoned.pcd");
  {
    mc::PcdStreamWriter w(a);
    w.add({1, 2, 3, 0});
  }
  EXPECT_FALSE(fs::exists(a));
  EXPECT_FALSE(fs::exists(a + ".partial"));
}

TEST(PointCloudIO, MalformedPcdErrorsNameTheFile) {
  const std::string f = tmp("bad.pcd");
  const auto expectError = [&](const std::string& text, const std::string& what) {
    writeText(f, text);
    try {
      mc::readPcd(f);
      FAIL() << "no error for: " << what;
    } catch (const mc::PointCloudFileError& e) {
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
    }
  };
  const std::string head =
      "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 2\nHEIGHT 1\nPOINTS 2\n";
  expectError(head + "DATA binary\n" + std::string(12, '\0'), "truncated");
  expectError(head + "DATA binary_packed\n", "unsupported DATA");  // binary_compressed is read
  expectError("FIELDS x y\nSIZE 4 4\nTYPE F F\nPOINTS 0\nDATA ascii\n", "no field 'z'");
  expectError("hello world\n", "not a PCD header line");
  expectError(head, "no DATA line");
  EXPECT_THROW(mc::readPcd(tmp("missing.pcd")), mc::PointCloudFileError);
}

TEST(PointCloudIO, PlyHeaderAndSize) {
  const std::string f = tmp("m.ply");
  mc::writePly(f, {{1, 2, 3, 4}, {5, 6, 7, 8}});
  std::ifstream in(f, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string s = ss.str();
  const auto end = s.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  EXPECT_NE(s.find("format binary_little_endian 1.0"), std::string::npos);
  EXPECT_NE(s.find("element vertex 2\n"), std::string::npos);
  EXPECT_EQ(s.size(), end + 11 + 2 * 16);
  float v[4];
  std::memcpy(v, s.data() + end + 11 + 16, sizeof(v));
  EXPECT_EQ(v[3], 8.f);
}

TEST(PointCloudIO, PlyRoundTrip) {
  const std::string f = tmp("rt.ply");
  const std::vector<mc::MapPoint> pts = {{1, 2, 3, 4}, {-5.5f, 6, 7e3f, 0}};
  mc::writePly(f, pts);
  const std::vector<mc::MapPoint> back = mc::readPly(f);
  ASSERT_EQ(back.size(), 2u);
  for (std::size_t i = 0; i < 2; i++) {
    EXPECT_EQ(back[i].x, pts[i].x);
    EXPECT_EQ(back[i].y, pts[i].y);
    EXPECT_EQ(back[i].z, pts[i].z);
    EXPECT_EQ(back[i].intensity, pts[i].intensity);
  }
}

TEST(PointCloudIO, PlyWithoutIntensityOrWithOtherFloats) {
  const std::string f = tmp("other.ply");
  const float v[4] = {9, 1, 2, 3};  // nx x y z
  std::ofstream(f, std::ios::binary)
      << "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float nx\n"
         "property float x\nproperty float y\nproperty float z\nend_header\n"
      << std::string(reinterpret_cast<const char*>(v), sizeof(v));
  const auto p = mc::readPly(f);
  ASSERT_EQ(p.size(), 1u);
  EXPECT_EQ(p[0].x, 1.f);
  EXPECT_EQ(p[0].z, 3.f);
  EXPECT_EQ(p[0].intensity, 0.f);
}

TEST(PointCloudIO, PlyErrorsNameTheFileAndTheProblem) {
  const auto message = [](const std::string& path) {
    try {
      mc::readPly(path);
    } catch (const mc::PointCloudFileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string f = tmp("bad.ply");
  writeText(f, "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n1\n");
  EXPECT_NE(message(f).find("bad.ply: format ascii: only binary_little_endian"), std::string::npos);
  writeText(f,
            "ply\nformat binary_little_endian 1.0\nelement vertex 2\nproperty float x\n"
            "property float y\nproperty float z\nend_header\n123456789012");
  EXPECT_NE(message(f).find("truncated: 1 of 2 vertices"), std::string::npos);
  writeText(f,
            "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty double x\n"
            "end_header\n");
  EXPECT_NE(message(f).find("vertex property 'x' is double"), std::string::npos);
  EXPECT_NE(message(tmp("none.ply")).find("cannot open it"), std::string::npos);
  writeText(f, "PCD\n");
  EXPECT_NE(message(f).find("not a PLY file"), std::string::npos);
}
