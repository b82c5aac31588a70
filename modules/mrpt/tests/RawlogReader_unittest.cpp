// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mrptio/RawlogReader.h>
#include <gtest/gtest.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CFileOutputStream.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>

#include <fstream>
#include <iterator>

using dynobj::mrptio::RawlogEntry;
using dynobj::mrptio::RawlogError;
using dynobj::mrptio::RawlogReader;

namespace {

std::string tempPath(const std::string& name) {
  return mrpt::system::getTempFileName() + "_" + name;
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
