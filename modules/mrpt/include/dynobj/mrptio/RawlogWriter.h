// SPDX-License-Identifier: BSD-3-Clause
// The output rawlog of every tool (rawlog-dynobj, dynobj-import, the simulator): written to
// "<path>.partial" (io::AtomicFile), renamed by commit(), removed when destroyed uncommitted.
//
// Format: what MRPT's CFileGZOutputStream writes, byte for byte once decompressed (objects
// serialized with CArchive one after the other), compressed as a sequence of independent gzip
// members of ~1 MiB each (ISA-L, GzipStream.h) instead of one zlib stream. A gzip file may hold
// several members (RFC 1952 §2.2); zlib's gzread(), hence MRPT's CFileGZInputStream and every stock
// MRPT tool, reads them all. Independent members can be compressed in parallel: with `threads` > 1,
// blocks are compressed by a pool of worker threads while the caller goes on serializing, and
// written in order. Level 0 writes a plain (uncompressed) rawlog, which MRPT reads as well.
#pragma once

#include <mrpt/serialization/CSerializable.h>

#include <memory>
#include <string>

#include "dynobj/mrptio/GzipStream.h"

namespace dynobj::mrptio {

class RawlogWriter {
 public:
  /// Uncompressed bytes per gzip member (a block is closed after the object that reaches it).
  static constexpr std::size_t kBlockBytes = 1u << 20;
  /// Highest `compress_level`.
  static constexpr int kMaxLevel = GzipMemberEncoder::kMaxLevel;

  /// `compress_level`: 0 = plain rawlog, 1 (fastest, default) .. 3 (smallest); `threads`:
  /// compression threads (1 = compress in the caller's thread). Throws std::invalid_argument on a
  /// bad level, std::runtime_error naming the file when it cannot be created.
  explicit RawlogWriter(const std::string& path, int compress_level = 1, unsigned threads = 1);
  ~RawlogWriter();
  RawlogWriter(const RawlogWriter&) = delete;
  RawlogWriter& operator=(const RawlogWriter&) = delete;

  /// One compression thread per hardware thread (at least 1).
  static unsigned hardwareThreads();

  /// Appends one object (an observation, a sensory frame, an action collection). It is
  /// serialized before this returns: the caller may change or free it afterwards. Blocks while
  /// too many blocks wait for compression (memory stays bounded). Throws std::runtime_error on a
  /// write error (naming the file) or a compression thread's error.
  void write(const mrpt::serialization::CSerializable& obj);
  /// Flushes, closes and renames into place. Throws std::runtime_error on failure.
  void commit();

  const std::string& path() const;
  /// Bytes written to the file so far (compressed).
  std::uint64_t bytesWritten() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dynobj::mrptio
