// SPDX-License-Identifier: BSD-3-Clause
// Checks a serialized MRPT object before MRPT deserializes it. MRPT 2.5 trusts the sizes it reads
// (a range image's rows x cols, a point count, a string length): a damaged size makes it ask for
// terabytes, and its aligned allocator returns nullptr instead of throwing, so the next memset
// crashes the process (docs/formats.md, "MRPT quirks"). The check walks the object's bytes in a
// look-ahead buffer for the classes our rawlogs hold, rejects sizes beyond sane limits or beyond
// the end of the stream, and only then lets MRPT read the same bytes from the buffer.
#pragma once

#include <mrpt/io/CStream.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynobj::mrptio::detail {

/// The object's bytes end before the object does.
class ObjectTruncated : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
/// A declared size beyond the limits, or a structure that cannot be right.
class ObjectDamaged : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// A read-only CStream over another one that can look ahead: check code reads bytes before MRPT
/// does, MRPT then reads them from the buffer (and the rest straight from the source).
class LookaheadStream : public mrpt::io::CStream {
 public:
  explicit LookaheadStream(std::unique_ptr<mrpt::io::CStream> source);

  /// Makes up to `n` unread bytes available at ahead(); returns how many are (fewer at the end
  /// of the source).
  std::size_t ensure(std::size_t n);
  const std::uint8_t* ahead() const { return buf_.data() + head_; }

  std::size_t Read(void* buf, std::size_t n) override;
  std::size_t Write(const void* buf, std::size_t n) override;
  std::uint64_t Seek(int64_t off, mrpt::io::CStream::TSeekOrigin origin) override;
  std::uint64_t getTotalBytesCount() const override;
  /// Bytes consumed by Read() (not counting the look-ahead).
  std::uint64_t getPosition() const override { return pos_; }

 private:
  std::size_t readSource(std::uint8_t* dst, std::size_t n);

  std::unique_ptr<mrpt::io::CStream> source_;
  std::vector<std::uint8_t> buf_;
  std::size_t head_ = 0;  ///< first unread byte in buf_
  std::uint64_t pos_ = 0;
};

/// Limits on what one serialized object may declare (well above any sensor: a 128 x 4096 LiDAR
/// image is 2^19 pixels, a 1920 x 1080 depth image 2^21).
struct ObjectLimits {
  std::uint64_t max_elements = 1ULL << 24;  ///< points, pixels of a range image / label layer
  std::uint64_t max_image_bytes = 1ULL << 28;
  std::uint64_t max_string = 1ULL << 16;
  std::uint64_t max_observations = 1ULL << 16;  ///< in one sensory frame
};

/// Walks the object that starts at `in`'s read position, without consuming it. Classes and
/// versions it knows (CObservation3DRangeScan v0-v10 with its CPose3D / CImage / TCamera /
/// CMatrixF members, CSensoryFrame v0-v2, CObservationOdometry, the count of a CActionCollection):
/// every size is checked and the whole object is then in the look-ahead buffer; a member object
/// of another class, or of a version a v9-v10 scan cannot hold, is damage. Class names resolve as
/// in MRPT (up to a NUL byte; a name not registered with its namespace is looked up without it).
/// Any other class or version: the walk stops there and MRPT reads it unchecked.
/// Throws ObjectTruncated / ObjectDamaged (naming the class and the offset inside the object).
/// Returns the number of bytes checked (0 at the end of the stream).
std::size_t checkNextObject(LookaheadStream& in, const ObjectLimits& limits = {});

}  // namespace dynobj::mrptio::detail
