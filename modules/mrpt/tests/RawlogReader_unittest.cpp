// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>

using dynobj::mrptio::RawlogEntry;
using dynobj::mrptio::RawlogError;
using dynobj::mrptio::RawlogReader;

namespace {

std::string tempPath(const std::string& name) {
  return dynobj::testing::scratchPath("_") + name;
}

/// Writes `n` comment observations (plain, uncompressed, so byte offsets are predictable).
std::string writeComments(int n, bool gz) {
  const std::string path = tempPath(gz ? "c.rawlog.gz" : "c.rawlog");
  auto write = [&](mrpt::io::CStream& s) {
    auto arch = mrpt::serialization::archiveFrom(s);
    for (int i = 0; i < n; i++) {
      mrpt::obs::CObservationComment c;
      c.text = "comment number " + std::to_string(i) + std::string(100, 'x');
      arch << c;
    }
  };
  if (gz) {
    mrpt::io::CFileGZOutputStream f(path);
    write(f);
  } else {
    mrpt::io::CFileOutputStream f(path);
    write(f);
  }
  return path;
}

std::string readAll(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

void writeAll(const std::string& path, const std::string& bytes) {
  std::ofstream f(path, std::ios::binary);
  f << bytes;
}

/// Reads to the end; returns the entries read before the error (or all), and the error text.
std::size_t readUntilError(const std::string& path, std::string& error) {
  RawlogReader reader(path);
  RawlogEntry e;
  try {
    while (reader.next(e)) {
    }
  } catch (const RawlogError& ex) {
    error = ex.what();
  }
  return reader.entriesRead();
}

}  // namespace

TEST(RawlogReader, ReadsBothFormats) {
  for (bool gz : {false, true}) {
    const auto path = writeComments(5, gz);
    std::string err;
    EXPECT_EQ(readUntilError(path, err), 5u);
    EXPECT_EQ(err, "");
  }
  // Format #1 (actions + sensory frames): MRPT's own ICP-SLAM demo log.
  RawlogReader sf(
      "/usr/share/mrpt/datasets/2006-01ENE-21-SENA_Telecom Faculty_one_loop_only.rawlog");
  RawlogEntry e;
  std::size_t n = 0, with_actions = 0;
  while (sf.next(e)) {
    n++;
    EXPECT_TRUE(e.isPair());
    EXPECT_FALSE(e.observations().empty());
    if (e.actions) with_actions++;
  }
  EXPECT_EQ(n, 225u);  // 449 objects: one leading sensory frame, then 224 (action, frame) pairs
  EXPECT_EQ(with_actions, 224u);
}

TEST(RawlogReader, MissingAndEmptyFilesAreErrors) {
  EXPECT_THROW(RawlogReader("/nonexistent/x.rawlog"), RawlogError);
  const auto empty = tempPath("empty.rawlog");
  writeAll(empty, "");
  try {
    RawlogReader r(empty);
    FAIL();
  } catch (const RawlogError& e) {
    EXPECT_NE(std::string(e.what()).find("is empty"), std::string::npos);
  }
}

TEST(RawlogReader, TruncatedFileIsAnErrorNamingTheEntry) {
  for (bool gz : {false, true}) {
    SCOPED_TRACE(gz ? "gzip" : "plain");
    const auto path = writeComments(5, gz);
    const std::string bytes = readAll(path);
    const auto cut = tempPath("cut.rawlog");
    // Cut inside an object. (A cut exactly between two objects cannot be told from a shorter
    // file: the rawlog format has no entry count. docs/formats.md says so.)
    writeAll(cut, bytes.substr(0, bytes.size() * 6 / 10 + 7));
    std::string err;
    const std::size_t read = readUntilError(cut, err);
    EXPECT_LT(read, 5u);
    EXPECT_NE(err, "") << "a truncated file must not look like a short one";
    EXPECT_NE(err.find("entry " + std::to_string(read)), std::string::npos) << err;
    EXPECT_NE(err.find("truncated"), std::string::npos) << err;
    EXPECT_EQ(err.find("backtrace"), std::string::npos) << err;
  }
}

TEST(RawlogReader, UnknownClassAndGarbageAreErrors) {
  // A well-formed object header naming a class nobody registered.
  const auto path = tempPath("unknown.rawlog");
  std::string obj;
  const std::string name = "mynamespace::CObservationNobodyKnows";
  obj.push_back(static_cast<char>(0x80 | name.size()));
  obj += name;
  obj.push_back(0);  // version
  obj.push_back(static_cast<char>(0x88));
  writeAll(path, readAll(writeComments(2, false)) + obj);
  std::string err;
  EXPECT_EQ(readUntilError(path, err), 2u);
  EXPECT_NE(err.find("entry 2"), std::string::npos) << err;
  EXPECT_NE(err.find("CObservationNobodyKnows"), std::string::npos) << err;

  const auto garbage = tempPath("garbage.rawlog");
  writeAll(garbage, std::string(1000, '\x42'));
  err.clear();
  EXPECT_EQ(readUntilError(garbage, err), 0u);
  EXPECT_NE(err, "");
}

namespace {

/// A plain rawlog of one small range scan (3 x 5 image, 2 points, pixel labels, a range layer);
/// `damage` edits its serialized bytes.
std::string writeRangeScan(const std::function<void(std::string&)>& damage) {
  mrpt::obs::CObservation3DRangeScan o;
  o.sensorLabel = "LIDAR";
  o.hasRangeImage = true;
  o.rangeImage_setSize(3, 5);
  o.rangeImage.fill(1000);
  o.hasPoints3D = true;
  o.resizePoints3DVectors(2);
  o.hasIntensityImage = true;
  o.intensityImage.resize(5, 3, mrpt::img::CH_GRAY);
  o.pixelLabels = std::make_shared<mrpt::obs::TPixelLabelInfo<1>>();
  o.pixelLabels->setSize(3, 5);
  o.pixelLabels->setLabelName(0, "dynamic");
  o.rangeImageOtherLayers["intensity"].setSize(3, 5);
  mrpt::io::CMemoryStream buf;
  mrpt::serialization::archiveFrom(buf) << o;
  std::string bytes(static_cast<const char*>(buf.getRawBufferData()), buf.getTotalBytesCount());
  damage(bytes);
  const auto path = tempPath("scan.rawlog");
  writeAll(path, readAll(writeComments(1, false)) + bytes);
  return path;
}

/// Replaces the first (or last) occurrence of the little-endian uint32 pair (a, b) by (na, nb).
void replacePair(std::string& s, std::uint32_t a, std::uint32_t b, std::uint32_t na,
                 std::uint32_t nb, bool last = false) {
  std::string from(8, '\0'), to(8, '\0');
  std::memcpy(&from[0], &a, 4), std::memcpy(&from[4], &b, 4);
  std::memcpy(&to[0], &na, 4), std::memcpy(&to[4], &nb, 4);
  const auto p = last ? s.rfind(from) : s.find(from);
  ASSERT_NE(p, std::string::npos);
  s.replace(p, 8, to);
}

}  // namespace

TEST(RawlogReader, IntactRangeScanPassesTheSizeCheck) {
  std::string err;
  EXPECT_EQ(readUntilError(writeRangeScan([](std::string&) {}), err), 2u) << err;
  EXPECT_EQ(err, "");
}

TEST(RawlogReader, DamagedRangeImageSizeIsAnErrorNotACrash) {
  // MRPT 2.5.8 alone dies of SIGSEGV on this (docs/upstream/): 1e6 x 1e5 pixels.
  std::string err;
  const auto path = writeRangeScan([](std::string& s) { replacePair(s, 3, 5, 1000000, 100000); });
  EXPECT_EQ(readUntilError(path, err), 1u);
  EXPECT_NE(err.find("is damaged at entry 1"), std::string::npos) << err;
  EXPECT_NE(err.find("the range image declares 1000000 x 100000 elements (limit 16777216)"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("CObservation3DRangeScan"), std::string::npos) << err;
}

TEST(RawlogReader, SizeBeyondTheEndOfTheFileIsTruncation) {
  std::string err;
  // 3 x 5 -> 300 x 500: within the limit, but the file does not hold 300,000 bytes of pixels.
  const auto path = writeRangeScan([](std::string& s) { replacePair(s, 3, 5, 300, 500); });
  EXPECT_EQ(readUntilError(path, err), 1u);
  EXPECT_NE(err.find("is truncated at entry 1"), std::string::npos) << err;
}

TEST(RawlogReader, DamagedPixelLabelAndLayerSizesAreErrors) {
  std::string err;
  // The label matrix is serialized as nR, nC = 3, 5 after the range image: its second
  // occurrence. The range layer is written as (cols, rows) = 5, 3, the last such pair (the grey
  // intensity image's width, height come earlier).
  auto labels = writeRangeScan([](std::string& s) {
    const std::string pair("\x03\0\0\0\x05\0\0\0", 8);
    const auto first = s.find(pair);
    const auto second = s.find(pair, first + 8);
    ASSERT_NE(second, std::string::npos);
    const std::uint32_t huge = 0x7FFFFFFF;
    std::memcpy(&s[second], &huge, 4);
  });
  EXPECT_EQ(readUntilError(labels, err), 1u);
  EXPECT_NE(err.find("the pixel labels declares 2147483647 x 5"), std::string::npos) << err;
  err.clear();
  auto layer = writeRangeScan([](std::string& s) { replacePair(s, 5, 3, 5, 0xFFFFFFFF, true); });
  EXPECT_EQ(readUntilError(layer, err), 1u);
  EXPECT_NE(err.find("a range image layer declares 5 x 4294967295"), std::string::npos) << err;
}

TEST(RawlogReader, ReadsFromAMemoryStream) {
  const std::string bytes = readAll(writeComments(3, false));
  auto mem = std::make_unique<mrpt::io::CMemoryStream>();
  mem->assignMemoryNotOwn(bytes.data(), bytes.size());  // `bytes` outlives the reader
  RawlogReader reader(std::move(mem), "memory");
  RawlogEntry e;
  std::size_t n = 0;
  while (reader.next(e)) n++;
  EXPECT_EQ(n, 3u);
}

TEST(RawlogReader, FileFractionGrowsToOneAndIsUnknownForAStream) {
  for (bool gz : {false, true}) {
    const auto path = writeComments(2000, gz);  // several read buffers, gzip or not
    RawlogReader reader(path);
    EXPECT_EQ(reader.fileFraction(), 0.0);
    RawlogEntry e;
    double last = 0;
    bool inside = false;  // some entry read with part of the file left
    while (reader.next(e)) {
      const double f = reader.fileFraction();
      EXPECT_GE(f, last);
      inside = inside || (f > 0 && f < 1);
      last = f;
    }
    EXPECT_TRUE(inside) << (gz ? "gzip" : "plain");
    EXPECT_DOUBLE_EQ(reader.fileFraction(), 1.0);
  }
  const std::string bytes = readAll(writeComments(3, false));
  auto mem = std::make_unique<mrpt::io::CMemoryStream>();
  mem->assignMemoryNotOwn(bytes.data(), bytes.size());
  EXPECT_LT(RawlogReader(std::move(mem), "memory").fileFraction(), 0);
}

TEST(RawlogReader, ClassNamesResolveAsInMrpt) {
  // Found by fuzzing: MRPT reads "nullptroses::CPose3D" as a CPose3D (it retries a name without
  // its namespace), so the check must walk it as one and still see the damaged size after it.
  std::string err;
  const auto path = writeRangeScan([](std::string& s) {
    const auto p = s.find("mrpt::poses::CPose3D");
    ASSERT_NE(p, std::string::npos);
    s.replace(p, 20, "nullptroses::CPose3D");
    replacePair(s, 3, 5, 1000000, 100000);
  });
  EXPECT_EQ(readUntilError(path, err), 1u);
  EXPECT_NE(err.find("the range image declares 1000000 x 100000"), std::string::npos) << err;
  // ... and the name ends at a NUL byte (MRPT reads it into a C string).
  err.clear();
  const auto nul = writeRangeScan([](std::string& s) {
    const auto p = s.find("mrpt::poses::CPose3D");
    ASSERT_NE(p, std::string::npos);
    s.replace(p, 20, std::string("CPose3D\0garbagegarb", 20));
    replacePair(s, 3, 5, 1000000, 100000);
  });
  EXPECT_EQ(readUntilError(nul, err), 1u);
  EXPECT_NE(err.find("the range image declares 1000000 x 100000"), std::string::npos) << err;
}

TEST(RawlogReader, MemberOfAnotherClassIsDamage) {
  std::string err;
  const auto path = writeRangeScan([](std::string& s) {
    const auto p = s.find("mrpt::img::CImage");
    ASSERT_NE(p, std::string::npos);
    s.replace(p, 17, "mrpt::img::XImage");
  });
  EXPECT_EQ(readUntilError(path, err), 1u);
  EXPECT_NE(err.find("a member object that should be a CImage is not"), std::string::npos) << err;
}

TEST(RawlogReader, OldSensoryFrameVersionsHaveTheirCountChecked) {
  // Found by fuzzing: a version-1 sensory frame (MRPT still reads it) declaring 2^32-1
  // observations made MRPT allocate them before reading any.
  const std::string name = "mrpt::obs::CSensoryFrame";
  std::string obj(1, static_cast<char>(0x80 | name.size()));
  obj += name;
  obj += std::string("\x01", 1) + std::string("\x07\0\0\0", 4) + std::string(4, '\xFF');
  const auto path = tempPath("sf1.rawlog");
  writeAll(path, obj + std::string(64, '\0'));
  std::string err;
  EXPECT_EQ(readUntilError(path, err), 0u);
  EXPECT_NE(err.find("a sensory frame of 4294967295 observations"), std::string::npos) << err;
}

TEST(RawlogReader, OldRangeScanVersionsHaveTheirSizesChecked) {
  // Found by fuzzing: a version-0 CObservation3DRangeScan (MRPT 2.5 still reads v0-v10) with a
  // damaged point count went to MRPT unchecked.
  mrpt::io::CMemoryStream pose;
  mrpt::serialization::archiveFrom(pose) << mrpt::poses::CPose3D();
  const std::string name = "mrpt::obs::CObservation3DRangeScan";
  std::string obj(1, static_cast<char>(0x80 | name.size()));
  obj += name + std::string(1, '\0') + std::string(4, '\0');  // version 0, maxRange
  obj += std::string(static_cast<const char*>(pose.getRawBufferData()), pose.getTotalBytesCount());
  obj += std::string("\xF0\xFF\xFF\xFF", 4);  // 4294967280 points
  const auto path = tempPath("scan0.rawlog");
  writeAll(path, obj + std::string(64, '\0'));
  std::string err;
  EXPECT_EQ(readUntilError(path, err), 0u);
  EXPECT_NE(err.find("points3D declares 4294967280 x 1 elements"), std::string::npos) << err;
}
