// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/LabelFile.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/system/filesystem.h>

#include <fstream>

using namespace dynobj::io;

namespace {

std::string temp(const std::string& name) {
  return dynobj::testing::scratchPath("") + name;
}

std::string writeText(const std::string& text) {
  const auto p = temp(".labels");
  std::ofstream(p) << text;
  return p;
}

std::string errorOf(const std::string& text) {
  try {
    LabelFile::read(writeText(text));
  } catch (const LabelFileError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(LabelFile, WriteReadRoundTrip) {
  const auto path = temp(".labels");
  {
    LabelFileWriter w(path, 4, 8);
    EXPECT_FALSE(::mrpt::system::fileExists(path));  // only the .partial until close()
    w.write(100, {});
    w.write(200, {0, 9, 31});
    w.close();
  }
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "# dynobj-labels v1 rows=4 cols=8\n100 0\n200 3 0 9 31\n");
  const auto f = LabelFile::read(path);
  EXPECT_EQ(f.rows, 4);
  EXPECT_EQ(f.cols, 8);
  ASSERT_EQ(f.sweeps.size(), 2u);
  EXPECT_EQ(f.sweeps[1].timestamp_ns, 200);
  EXPECT_EQ(f.sweeps[1].pixels, (std::vector<std::uint32_t>{0, 9, 31}));
}

TEST(LabelFile, UnclosedWriterLeavesNoFile) {
  const auto path = temp(".labels");
  {
    LabelFileWriter w(path, 2, 2);
    w.write(1, {3});
  }
  EXPECT_FALSE(::mrpt::system::fileExists(path));
  EXPECT_FALSE(::mrpt::system::fileExists(path + ".partial"));
}

TEST(LabelFile, ErrorsNameTheLine) {
  EXPECT_NE(errorOf("").find(":1: empty"), std::string::npos);
  EXPECT_NE(errorOf("# dynobj-labels v2 rows=4 cols=8\n").find(":1: bad header"),
            std::string::npos);
  const std::string h = "# dynobj-labels v1 rows=4 cols=8\n";
  EXPECT_NE(errorOf(h + "10 1 32\n").find(":2: index 32 is outside the 4x8"), std::string::npos);
  EXPECT_NE(errorOf(h + "10 2 5 3\n").find(":2: indices are not strictly ascending"),
            std::string::npos);
  EXPECT_NE(errorOf(h + "10 0\n20 2 1\n").find(":3: count says 2 but 1"), std::string::npos);
  EXPECT_NE(errorOf(h + "10 0\n10 0\n").find(":3: timestamp 10 is not after"), std::string::npos);
  EXPECT_NE(errorOf(h + "10 1 x\n").find(":2: non-numeric"), std::string::npos);
  EXPECT_NE(errorOf(h + "abc\n").find(":2: expected"), std::string::npos);
  // Found by fuzzing: a huge count reserved gigabytes before the indices were read.
  EXPECT_NE(errorOf(h + "10 2000000000 1\n").find(":2: count 2000000000 is more than the 4x8"),
            std::string::npos);
  EXPECT_NE(errorOf(h + "10 33 1\n").find(":2: count 33 is more than"), std::string::npos);
  // ... and a header of 64 x 5,120,070,100 pixels (int overflow) let a 1.5e9 count through.
  EXPECT_NE(errorOf("# dynobj-labels v1 rows=64 cols=5120070100\n").find(":1: bad header"),
            std::string::npos);
  EXPECT_NE(errorOf("# dynobj-labels v1 rows=64 cols=70000\n").find("at most 65535"),
            std::string::npos);
  EXPECT_EQ(errorOf(h + "10 0\n"), "");
}

TEST(LabelFile, PixelsOfMaskAscending) {
  cv::Mat_<std::uint8_t> m(2, 3, std::uint8_t{0});
  m(1, 0) = 1;
  m(0, 2) = 255;
  EXPECT_EQ(pixelsOfMask(m), (std::vector<std::uint32_t>{2, 3}));
}

TEST(LabelFile, InstanceFileRoundTripAndErrors) {
  const auto path = temp(".instances");
  {
    LabelFileWriter w(path, 4, 8, true);
    w.write(100, {});
    w.write(200, {3, 9}, {7, 2});
    EXPECT_THROW(w.write(300, {1}), std::invalid_argument);  // an id per pixel is required
    w.close();
  }
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "# dynobj-instances v1 rows=4 cols=8\n100 0\n200 2 3:7 9:2\n");
  const LabelFile f = LabelFile::read(path);
  EXPECT_TRUE(f.instances);
  ASSERT_EQ(f.sweeps.size(), 2u);
  EXPECT_EQ(f.sweeps[1].pixels, (std::vector<std::uint32_t>{3, 9}));
  EXPECT_EQ(f.sweeps[1].ids, (std::vector<std::int32_t>{7, 2}));
  EXPECT_NE(errorOf("# dynobj-instances v1 rows=4 cols=8\n100 1 3\n")
                .find(":2: expected '<idx>:<id>' at pixel 3"),
            std::string::npos);
  EXPECT_TRUE(LabelFile::read(writeText("# dynobj-labels v1 rows=4 cols=8\n100 1 3\n"))
                  .sweeps[0]
                  .ids.empty());
}

TEST(LabelFile, ReviewedLineRoundTripsAndOldFilesCountAsReviewed) {
  const auto p = temp(".reviewed.labels");
  {
    LabelFileWriter w(p, 2, 3);
    w.writeReviewed({1, 1, 0, 1});
    for (int k = 0; k < 4; k++) w.write(10 + k, {static_cast<std::uint32_t>(k)});
    w.close();
  }
  std::ifstream in(p);
  std::string l1, l2;
  std::getline(in, l1);
  std::getline(in, l2);
  EXPECT_EQ(l2, "# reviewed 0-1,3");
  LabelFile f = LabelFile::read(p);
  ASSERT_EQ(f.sweeps.size(), 4u);
  EXPECT_TRUE(f.has_review);
  EXPECT_EQ(f.unreviewedSweeps(), (std::vector<std::size_t>{2}));
  EXPECT_THROW(f.requireReviewed(p), LabelFileError);
  f.keepReviewedOnly();
  ASSERT_EQ(f.sweeps.size(), 3u);
  EXPECT_EQ(f.sweeps[2].timestamp_ns, 13);
  EXPECT_NO_THROW(f.requireReviewed(p));

  const auto old = temp(".old.labels");  // no '# reviewed' line: every sweep counts
  {
    LabelFileWriter w(old, 2, 3);
    w.write(1, {});
    w.close();
  }
  const LabelFile o = LabelFile::read(old);
  EXPECT_FALSE(o.has_review);
  EXPECT_TRUE(o.unreviewedSweeps().empty());
}

TEST(LabelFile, SweepRangesParseStrictly) {
  EXPECT_EQ(formatSweepRanges({0, 0}), "none");
  EXPECT_EQ(formatSweepRanges({1, 0, 1, 1, 1}), "0,2-4");
  EXPECT_EQ(parseSweepRanges("0,2-4", 5), (std::vector<std::uint8_t>{1, 0, 1, 1, 1}));
  EXPECT_EQ(parseSweepRanges("none", 2), (std::vector<std::uint8_t>{0, 0}));
  EXPECT_THROW(parseSweepRanges("0-5", 5), std::invalid_argument);
  EXPECT_THROW(parseSweepRanges("3-1", 5), std::invalid_argument);
  EXPECT_THROW(parseSweepRanges("1;2", 5), std::invalid_argument);
  EXPECT_THROW(parseSweepRanges("", 5), std::invalid_argument);
  EXPECT_THROW(parseSweepRanges("1,", 5), std::invalid_argument);
  const auto p = temp(".badreview.labels");
  std::ofstream(p) << "# dynobj-labels v1 rows=1 cols=1\n# reviewed 0-3\n1 0\n";
  try {
    LabelFile::read(p);
    FAIL();
  } catch (const LabelFileError& e) {
    EXPECT_NE(std::string(e.what()).find(":2: bad '# reviewed' line"), std::string::npos)
        << e.what();
  }
}
