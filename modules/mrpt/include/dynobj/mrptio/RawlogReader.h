// SPDX-License-Identifier: BSD-3-Clause
// Streaming rawlog reader that tells a clean end of file from a damaged one. Stock
// CRawlog::getActionObservationPairOrObservation() returns false for both; this reader throws a
// RawlogError naming the entry instead, so no tool of ours mistakes a truncated file for a short
// one. Objects of the classes our rawlogs hold are checked before MRPT deserializes them
// (damaged sizes make MRPT 2.5 crash: docs/formats.md, "MRPT quirks").
#pragma once

#include <mrpt/io/CStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservation.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/serialization/CArchive.h>

#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynobj::mrptio {

class GzipInputStream;

/// A rawlog that cannot be opened or read to its end. what() names the file and the entry.
class RawlogError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// One entry: either an (actions, sensory frame) pair (rawlog format #1) or one observation
/// (format #2).
struct RawlogEntry {
  std::size_t index = 0;  ///< 0-based entry number (a pair counts as one entry)
  mrpt::obs::CActionCollection::Ptr actions;
  mrpt::obs::CSensoryFrame::Ptr sensory_frame;
  mrpt::obs::CObservation::Ptr observation;

  bool isPair() const { return sensory_frame != nullptr; }
  /// The entry's observations: the sensory frame's, or the single one.
  std::vector<mrpt::obs::CObservation::Ptr> observations() const;
};

class RawlogReader {
 public:
  /// Opens `path` (gzip or plain). Throws RawlogError if it is missing, empty or unreadable.
  explicit RawlogReader(const std::string& path);
  /// Reads an already open stream (e.g. a mrpt::io::CMemoryStream); `name` is used in messages.
  RawlogReader(std::unique_ptr<mrpt::io::CStream> stream, const std::string& name);
  ~RawlogReader();
  RawlogReader(const RawlogReader&) = delete;
  RawlogReader& operator=(const RawlogReader&) = delete;

  /// Reads the next entry. Returns false at a clean end of file; throws RawlogError on a
  /// truncated or corrupt file, or an object of an unregistered or unexpected class.
  bool next(RawlogEntry& entry);

  const std::string& path() const { return path_; }
  std::size_t entriesRead() const { return entries_; }
  /// Uncompressed bytes consumed so far.
  std::uint64_t position() const;
  /// The share of the file read so far (0-1; its bytes on disk, compressed or not); negative for
  /// a reader of a stream.
  double fileFraction() const;

 private:
  mrpt::serialization::CSerializable::Ptr readObject(const char* what);

  struct Input;
  std::string path_;
  std::unique_ptr<Input> in_;
  const GzipInputStream* file_ = nullptr;  ///< the file (opened by path), in in_
  std::size_t entries_ = 0;
};

}  // namespace dynobj::mrptio
