// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/mrptio/RawlogWriter.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <isa-l/igzip_lib.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservationComment.h>
#include <mrpt/obs/CRawlog.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt/system/filesystem.h>

#include <filesystem>
#include <fstream>
#include <iterator>

using dynobj::mrptio::RawlogEntry;
using dynobj::mrptio::RawlogReader;
using dynobj::mrptio::RawlogWriter;

namespace {

std::string tempPath(const std::string& name) {
  return dynobj::testing::scratchPath("_") + name;
}

/// Comment i: ~`size` bytes of text that compresses somewhat (a counter among repeated words).
mrpt::obs::CObservationComment comment(int i, std::size_t size) {
  mrpt::obs::CObservationComment c;
  c.sensorLabel = "NOTE";
  c.timestamp = mrpt::Clock::fromDouble(1000.0 + i);  // (the default is 'now')
  while (c.text.size() < size)
    c.text += "comment " + std::to_string(i * 7919 + c.text.size()) + ";";
  return c;
}

const int kComments = 48;
const std::size_t kSize = 100000;  // 48 x 100 kB: five 1-MiB blocks

std::string readFile(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(f), {}};
}

/// Everything MRPT's CFileGZInputStream (zlib's gzread) decompresses from `path`.
std::string decompressWithMrpt(const std::string& path) {
  mrpt::io::CFileGZInputStream in(path);
  std::string out;
  char buf[65536];
  for (;;) {
    const std::size_t n = in.Read(buf, sizeof(buf));
    if (n == 0) break;
    out.append(buf, n);
  }
  return out;
}

/// The number of gzip members in `bytes` (each inflated on its own by ISA-L), -1 if damaged.
int countMembers(const std::string& bytes, std::size_t total_out) {
  std::vector<std::uint8_t> out(total_out);
  inflate_state st;
  std::size_t pos = 0;
  int members = 0;
  while (pos < bytes.size()) {
    isal_inflate_init(&st);
    st.crc_flag = ISAL_GZIP;
    st.next_in = reinterpret_cast<std::uint8_t*>(const_cast<char*>(bytes.data() + pos));
    st.avail_in = static_cast<std::uint32_t>(bytes.size() - pos);
    st.next_out = out.data();
    st.avail_out = static_cast<std::uint32_t>(out.size());
    if (isal_inflate(&st) != ISAL_DECOMP_OK || st.block_state != ISAL_BLOCK_FINISH) return -1;
    pos = bytes.size() - st.avail_in;
    members++;
  }
  return members;
}

int expectedMembers() {
  int members = 0;
  std::size_t block = 0;
  for (int i = 0; i < kComments; i++) {
    mrpt::io::CMemoryStream m;
    auto arch = mrpt::serialization::archiveFrom(m);
    arch << comment(i, kSize);
    block += m.getTotalBytesCount();
    if (block >= RawlogWriter::kBlockBytes) members++, block = 0;
  }
  return members + (block > 0 ? 1 : 0);
}

std::string writeComments(const std::string& name, int level, unsigned threads) {
  const std::string path = tempPath(name);
  RawlogWriter w(path, level, threads);
  for (int i = 0; i < kComments; i++) w.write(comment(i, kSize));
  w.commit();
  return path;
}

}  // namespace

TEST(RawlogWriter, StockReaderDecompressesEveryMemberToTheSameBytes) {
  // The reference: the same objects through MRPT's own gzip stream.
  const std::string ref_path = tempPath("ref.rawlog");
  {
    mrpt::io::CFileGZOutputStream f(ref_path);
    auto arch = mrpt::serialization::archiveFrom(f);
    for (int i = 0; i < kComments; i++) arch << comment(i, kSize);
  }
  const std::string reference = decompressWithMrpt(ref_path);
  ASSERT_GT(reference.size(), 4 * RawlogWriter::kBlockBytes);

  for (int level : {1, 3}) {
    for (unsigned threads : {1u, 3u}) {
      SCOPED_TRACE("level " + std::to_string(level) + ", threads " + std::to_string(threads));
      const std::string path = writeComments("l.rawlog", level, threads);
      EXPECT_EQ(decompressWithMrpt(path), reference);
      const std::string file = readFile(path);
      EXPECT_LT(file.size(), reference.size());
      // One member per block: closed by the object that fills 1 MiB, and the rest at the end.
      EXPECT_EQ(countMembers(file, reference.size()), expectedMembers());
      // And entry by entry through our reader (zlib under MRPT).
      RawlogReader r(path);
      RawlogEntry e;
      int n = 0;
      while (r.next(e)) {
        auto c = std::dynamic_pointer_cast<mrpt::obs::CObservationComment>(e.observation);
        ASSERT_TRUE(c);
        EXPECT_EQ(c->text, comment(n, kSize).text);
        n++;
      }
      EXPECT_EQ(n, kComments);
    }
  }
}

TEST(RawlogWriter, RawLogViewersLoaderReadsEveryMember) {
  // RawLogViewer (and CRawlog users) load a whole file with CRawlog::loadFromRawLogFile (which
  // keeps comments aside: laser scans here). 40 scans of ~150 kB: several members.
  const int n = 40, rays = 30000;
  for (int level : {0, 1}) {
    const std::string path = tempPath("viewer.rawlog");
    {
      RawlogWriter w(path, level, 3);
      for (int i = 0; i < n; i++) {
        mrpt::obs::CObservation2DRangeScan scan;
        scan.sensorLabel = "LASER";
        scan.timestamp = mrpt::Clock::fromDouble(1000.0 + i);
        scan.resizeScan(rays);
        for (int k = 0; k < rays; k++) {
          scan.setScanRange(k, static_cast<float>((i * rays + k) % 9973) * 0.001f);
          scan.setScanRangeValidity(k, true);
        }
        w.write(scan);
      }
      w.commit();
    }
    mrpt::obs::CRawlog log;
    ASSERT_TRUE(log.loadFromRawLogFile(path));
    ASSERT_EQ(log.size(), static_cast<std::size_t>(n));
    auto last =
        std::dynamic_pointer_cast<mrpt::obs::CObservation2DRangeScan>(log.getAsObservation(n - 1));
    ASSERT_TRUE(last);
    EXPECT_EQ(last->getScanRange(rays - 1),
              static_cast<float>(((n - 1) * rays + rays - 1) % 9973) * 0.001f);
  }
}

TEST(RawlogWriter, LevelZeroIsAPlainRawlog) {
  const std::string path = writeComments("plain.rawlog", 0, 2);
  const std::string file = readFile(path);
  ASSERT_GT(file.size(), 2u);
  EXPECT_FALSE(static_cast<unsigned char>(file[0]) == 0x1f &&
               static_cast<unsigned char>(file[1]) == 0x8b);
  EXPECT_EQ(decompressWithMrpt(path), file);  // MRPT reads it as it is
}

TEST(RawlogWriter, SameContentAndMembersWhateverTheThreads) {
  // What the docs promise: the same bytes once decompressed, cut into the same gzip members (one
  // per block, in file order). The compressed bytes are not promised: they are ISA-L's choice.
  const std::string p1 = writeComments("t1.rawlog", 1, 1);
  const std::string p4 = writeComments("t4.rawlog", 1, 4);
  const std::string a = decompressWithMrpt(p1), b = decompressWithMrpt(p4);
  EXPECT_EQ(a.size(), b.size());
  EXPECT_TRUE(a == b);  // (not EXPECT_EQ: it would print megabytes)
  const int members = countMembers(readFile(p1), a.size());
  EXPECT_EQ(members, 5);  // 48 x 100 kB in 1-MiB blocks
  EXPECT_EQ(countMembers(readFile(p4), b.size()), members);
}

TEST(RawlogWriter, UncommittedOutputIsRemoved) {
  const std::string path = tempPath("uncommitted.rawlog");
  {
    RawlogWriter w(path, 1, 2);
    for (int i = 0; i < 15; i++) w.write(comment(i, kSize));  // blocks in flight
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}

TEST(RawlogWriter, BadLevelNamesTheRange) {
  const std::string path = tempPath("bad-level.rawlog");
  try {
    RawlogWriter w(path, 4);
    FAIL() << "accepted level 4";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("0..3"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".partial"));
}
