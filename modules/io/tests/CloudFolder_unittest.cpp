// SPDX-License-Identifier: BSD-3-Clause
// CloudFolder: name order, times files in their three forms, folder errors, and the 22 real
// KITTI HDL-64 sweeps of ../shared/realdata read end to end.
#include <dynobj/io/CloudFolder.h>
#include <dynobj/io/PcdFile.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <numeric>

namespace io = dynobj::io;
namespace fs = std::filesystem;

namespace {

/// A fresh scratch folder holding empty-named sweeps `files` (KITTI .bin: one point each).
std::string folder(const std::string& name, const std::vector<std::string>& files) {
  const fs::path d = fs::path(::testing::TempDir()) / ("dynobj-io-folder-" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  for (const std::string& f : files) {
    const float v[4] = {static_cast<float>(f.size()), 0, 0, 0};
    std::ofstream(d / f, std::ios::binary).write(reinterpret_cast<const char*>(v), sizeof(v));
  }
  return d.string();
}

std::string text(const std::string& name, const std::string& content) {
  const std::string p = ::testing::TempDir() + "dynobj-io-folder-" + name;
  std::ofstream(p) << content;
  return p;
}

void expectError(const std::function<void()>& f, const std::string& what) {
  try {
    f();
    ADD_FAILURE() << "no error for: " << what;
  } catch (const io::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(CloudFolder, NaturalNameOrderAndDefaultStamps) {
  const std::string d = folder("order", {"10.bin", "2.bin", "1.bin", "notes.txt", "02b.bin"});
  io::CloudFolder f(d);
  ASSERT_EQ(f.size(), 4u);
  std::vector<std::string> names;
  for (std::size_t k = 0; k < f.size(); k++) names.push_back(fs::path(f.path(k)).filename());
  EXPECT_EQ(names, (std::vector<std::string>{"1.bin", "2.bin", "02b.bin", "10.bin"}));
  EXPECT_EQ(f.extension(), ".bin");
  EXPECT_FALSE(f.hasTimes());
  EXPECT_EQ(f.timestampNs(3), 300000000);  // 10 Hz from 0 unless told otherwise
  f.setPeriodNs(50000000);
  EXPECT_EQ(f.timestampNs(3), 150000000);
  EXPECT_THROW(f.setPeriodNs(0), std::invalid_argument);
  EXPECT_THROW(f.timestampNs(4), std::out_of_range);
  EXPECT_EQ(f.read(3).cloud.x, std::vector<float>{6});  // "10.bin": x = name length
}

TEST(CloudFolder, TimesFilesInSecondsNanosecondsAndDates) {
  const std::string d = folder("times", {"a.bin", "b.bin", "c.bin"});
  io::CloudFolder s(d, text("s.txt", "0.000000e+00\n1.036602e-01\n\n# gap\n0.2073\n"));
  EXPECT_TRUE(s.hasTimes());
  EXPECT_EQ(s.timestampNs(1), 103660200);
  EXPECT_EQ(s.timestampNs(2), 207300000);
  io::CloudFolder ns(d, text("ns.txt",
                             "1317354879000000000\n1317354879100000000\n"
                             "1317354879200000001\n"));
  EXPECT_EQ(ns.timestampNs(2), 1317354879200000001);
  io::CloudFolder dt(d, text("dt.txt",
                             "2011-09-26 13:02:25.964389445\n"
                             "2011-09-26 13:02:26.064389445\n2012-03-01 00:00:00\n"));
  EXPECT_EQ(dt.timestampNs(0), 1317042145964389445);  // checked with `date -u -d @1317042145`
  EXPECT_EQ(dt.timestampNs(1) - dt.timestampNs(0), 100000000);
  EXPECT_EQ(dt.timestampNs(2), 1330560000000000000);  // after 29 Feb 2012
}

TEST(CloudFolder, ErrorsNameTheFolderOrTheLine) {
  const std::string d = folder("err", {"a.bin", "b.bin"});
  expectError([&] { io::CloudFolder(d, text("few.txt", "0.1\n")); },
              "few.txt: 1 time stamps for 2 sweeps in " + d);
  expectError([&] { io::CloudFolder(d, text("back.txt", "0.2\n0.1\n")); },
              "back.txt:2: time stamp '0.1' is not after the previous one");
  expectError([&] { io::CloudFolder(d, text("junk.txt", "0.1\nsoon\n")); },
              "junk.txt:2: 'soon' is not a time stamp");
  const std::string empty = folder("empty", {"readme.txt"});
  expectError([&] { io::CloudFolder{empty}; }, empty + ": holds no .pcd or .bin file");
  const std::string mixed = folder("mixed", {"0.bin", "1.PCD", "2.pcd"});
  expectError([&] { io::CloudFolder{mixed}; }, "holds both .pcd (2) and .bin (1) files");
  expectError([&] { io::CloudFolder{d + "/nope"}; }, "not a folder");
}

TEST(CloudFolder, PcdFolderDispatchesToReadPcd) {
  const std::string d = folder("pcd", {});
  dynobj::core::PointCloud c;
  c.push_back(1, 2, 3, 7);
  io::writePcd(d + "/000001.pcd", c);
  io::writePcd(d + "/000000.pcd", dynobj::core::PointCloud{});
  io::CloudFolder f(d);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_EQ(f.extension(), ".pcd");
  EXPECT_TRUE(f.read(0).cloud.empty());
  EXPECT_EQ(f.read(1).cloud.intensity, std::vector<float>{7});
}

TEST(CloudFolder, RealKittiHdl64Sweeps) {
  const std::string dir = DYNOBJ_SOURCE_DIR "/../shared/realdata/kitti-hdl64-city-22";
  if (!fs::is_directory(dir))
    GTEST_SKIP() << "../shared/realdata/kitti-hdl64-city-22 not found: real-data test skipped";
  io::CloudFolder f(dir);
  ASSERT_EQ(f.size(), 22u);
  double seconds = 0;
  std::size_t fewest = ~std::size_t{0}, most = 0;
  for (std::size_t k = 0; k < f.size(); k++) {
    const auto t0 = std::chrono::steady_clock::now();
    const io::CloudFile c = f.read(k);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    SCOPED_TRACE(f.path(k));
    const std::size_t n = c.cloud.size();
    fewest = std::min(fewest, n);
    most = std::max(most, n);
    EXPECT_GE(n, 114000u);
    EXPECT_LT(n, 122000u);  // 114-121 k
    EXPECT_EQ(c.width, n);
    EXPECT_EQ(c.dropped_nonfinite, 0u);
    EXPECT_EQ(c.intensity_field, "intensity");
    ASSERT_EQ(c.cloud.intensity.size(), n);
    const auto [lo, hi] = std::minmax_element(c.cloud.intensity.begin(), c.cloud.intensity.end());
    EXPECT_GE(*lo, 0.f);
    EXPECT_LT(*hi, 1.f);
    EXPECT_TRUE(c.time_s.empty());
    EXPECT_FALSE(c.cloud.hasRing());
    EXPECT_TRUE(c.viewpoint.isApprox(Eigen::Isometry3d::Identity()));
    EXPECT_EQ(f.timestampNs(k), static_cast<std::int64_t>(k) * 100000000);
    if (k == 0) {  // figures from an independent parse of the file (Python struct)
      EXPECT_EQ(n, 119978u);
      EXPECT_NEAR(std::accumulate(c.cloud.x.begin(), c.cloud.x.end(), 0.0), -48767.579, 1e-2);
      EXPECT_EQ(*hi, 0.99f);
      EXPECT_EQ(c.cloud.x.back(), 0.f);  // PCL wrote a last (0,0,0) point, kept as stored
      EXPECT_EQ(c.cloud.z.back(), 0.f);
    }
  }
  std::cout << "[ real data ] 22 sweeps, " << fewest << "-" << most << " points, "
            << 1e3 * seconds / 22 << " ms per sweep\n";
}
