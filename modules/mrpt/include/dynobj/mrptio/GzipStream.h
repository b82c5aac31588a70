// SPDX-License-Identifier: BSD-3-Clause
// The gzip side of our rawlogs, with Intel's ISA-L (igzip, Debian libisal-dev) instead of zlib:
// measured on the `hall` rawlog, its deflate (level 1) is ~15x faster than zlib's level 1 for a
// 3 % larger file, its inflate ~2x faster (docs/performance.md, "Compression"). The files are
// ordinary gzip (RFC 1952), read by zlib and therefore by every stock MRPT tool.
//
// GzipMemberEncoder: one block of bytes -> one complete gzip member. A gzip file may hold several
//   members one after the other (RFC 1952 §2.2); zlib's gzread() (MRPT's CFileGZInputStream)
//   reads through all of them, so blocks can be compressed independently, in parallel.
// GzipInputStream: the mrpt::io::CStream RawlogReader reads from: a gzip file of one or several
//   members, or a plain file (as CFileGZInputStream, which it replaces).
#pragma once

#include <mrpt/io/CStream.h>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace dynobj::mrptio {

class GzipMemberEncoder {
 public:
  static constexpr int kMaxLevel = 3;  ///< ISA-L's highest level

  /// `level`: 0 = no compression (encode() copies), 1 (fastest) .. 3. Throws
  /// std::invalid_argument naming the range otherwise.
  explicit GzipMemberEncoder(int level);
  ~GzipMemberEncoder();
  GzipMemberEncoder(const GzipMemberEncoder&) = delete;
  GzipMemberEncoder& operator=(const GzipMemberEncoder&) = delete;

  /// `raw` as one gzip member (a copy at level 0) into `out` (replaced).
  void encode(const std::string& raw, std::string& out);
  int level() const { return level_; }

 private:
  int level_;
  std::vector<std::uint8_t> level_buf_;  // ISA-L's per-level work memory
};

class GzipInputStream : public mrpt::io::CStream {
 public:
  GzipInputStream();
  ~GzipInputStream() override;
  GzipInputStream(const GzipInputStream&) = delete;
  GzipInputStream& operator=(const GzipInputStream&) = delete;

  /// Opens `path`; false (and `error`) when it cannot be opened.
  bool open(const std::string& path, std::string& error);

  /// Decompressed bytes; fewer than `count` only at the end of the data (or of a truncated
  /// file). Throws std::runtime_error on damaged gzip data (once; later calls return 0).
  size_t Read(void* buffer, size_t count) override;
  size_t Write(const void*, size_t) override;
  uint64_t Seek(int64_t, CStream::TSeekOrigin) override;
  /// The file's size on disk.
  uint64_t getTotalBytesCount() const override;
  /// Decompressed bytes read so far.
  uint64_t getPosition() const override;
  bool isGzip() const { return gzip_; }
  /// Bytes of the file (compressed, for gzip) decompressed so far: with getTotalBytesCount(), how
  /// much of the file has been read.
  std::uint64_t fileBytesRead() const { return consumed_ - (in_end_ - in_start_); }

 private:
  bool fill();  // more compressed input; false at the end of the file
  /// Up to `cap` decompressed bytes into `dst`; 0 at the end of the data.
  std::size_t inflateInto(std::uint8_t* dst, std::size_t cap);

  std::FILE* file_ = nullptr;
  std::string path_;
  bool gzip_ = false, eof_ = false, failed_ = false, member_done_ = false;
  std::uint64_t position_ = 0, file_size_ = 0, consumed_ = 0;
  std::vector<std::uint8_t> in_, out_;
  std::size_t in_start_ = 0, in_end_ = 0, out_start_ = 0, out_end_ = 0;
  struct State;
  std::unique_ptr<State> state_;  // ISA-L's inflate_state
};

}  // namespace dynobj::mrptio
