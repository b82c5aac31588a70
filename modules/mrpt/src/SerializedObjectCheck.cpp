// SPDX-License-Identifier: BSD-3-Clause
// The serialized layouts walked here are MRPT 2.5.8's serializeTo()/serializeFrom() of the classes
// named (libs/obs/src/CObservation3DRangeScan.cpp, libs/img/src/CImage.cpp, TCamera.cpp, ...).
#include "SerializedObjectCheck.h"

#include <algorithm>
#include <cstring>

namespace dynobj::mrptio::detail {

// ---------------------------------------------------------------- LookaheadStream

LookaheadStream::LookaheadStream(std::unique_ptr<mrpt::io::CStream> source)
    : source_(std::move(source)) {}

std::size_t LookaheadStream::ensure(std::size_t n) {
  std::size_t have = buf_.size() - head_;
  if (have >= n) return n;
  if (head_ > 0) {  // drop what was consumed
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(head_));
    head_ = 0;
  }
  constexpr std::size_t kChunk = 1 << 16;
  while (have < n) {
    const std::size_t want = std::max(n - have, kChunk);
    buf_.resize(have + want);
    const std::size_t got = readSource(buf_.data() + have, want);
    have += got;
    buf_.resize(have);
    if (got == 0) break;
  }
  return std::min(have, n);
}

std::size_t LookaheadStream::Read(void* out, std::size_t n) {
  auto* dst = static_cast<std::uint8_t*>(out);
  const std::size_t from_buf = std::min(n, buf_.size() - head_);
  if (from_buf > 0) {
    std::memcpy(dst, buf_.data() + head_, from_buf);
    head_ += from_buf;
    if (head_ == buf_.size()) buf_.clear(), head_ = 0;
  }
  std::size_t got = from_buf;
  if (got < n) got += readSource(dst + got, n - got);
  pos_ += got;
  return got;
}

std::size_t LookaheadStream::readSource(std::uint8_t* dst, std::size_t n) {
  const std::size_t got = source_->Read(dst, n);
  // CFileGZInputStream::Read returns gzread()'s -1 (as SIZE_MAX) on corrupt gzip data.
  if (got > n) throw ObjectDamaged("the gzip data is corrupt (zlib reports an error)");
  return got;
}

std::size_t LookaheadStream::Write(const void*, std::size_t) {
  throw std::logic_error("LookaheadStream is read-only");
}

std::uint64_t LookaheadStream::Seek(int64_t, mrpt::io::CStream::TSeekOrigin) {
  throw std::logic_error("LookaheadStream cannot seek");
}

std::uint64_t LookaheadStream::getTotalBytesCount() const {
  return source_->getTotalBytesCount();
}

// ---------------------------------------------------------------- the object walk

namespace {

constexpr std::uint8_t kEndFlag = 0x88;  // MRPT's SERIALIZATION_END_FLAG

/// Reads ahead of the stream's read position without consuming anything.
class Cursor {
 public:
  Cursor(LookaheadStream& in, const ObjectLimits& limits) : in_(in), limits_(limits) {}

  const std::uint8_t* take(std::uint64_t n) {
    const std::uint64_t end = off_ + n;
    if (end < off_ || in_.ensure(static_cast<std::size_t>(end)) < end)
      throw ObjectTruncated("the stream ends inside " + where());
    const std::uint8_t* p = in_.ahead() + off_;
    off_ = end;
    return p;
  }
  void skip(std::uint64_t n) { take(n); }
  std::uint8_t u8() { return *take(1); }
  std::uint32_t u32() {
    const std::uint8_t* p = take(4);
    return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
           static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
  }
  std::int32_t i32() { return static_cast<std::int32_t>(u32()); }
  bool flag(const char* what) {
    const std::uint8_t b = u8();
    if (b > 1) damaged(std::string(what) + " is " + std::to_string(b) + ", not a boolean");
    return b != 0;
  }
  std::string string(const char* what) {
    const std::uint32_t n = u32();
    if (n > limits_.max_string)
      damaged(std::string(what) + " declares a string of " + std::to_string(n) + " bytes (limit " +
              std::to_string(limits_.max_string) + ")");
    const std::uint8_t* p = take(n);
    return std::string(reinterpret_cast<const char*>(p), n);
  }
  /// rows x cols elements of `bytes` each: checked against the limit and skipped.
  void matrix(const char* what, std::uint64_t rows, std::uint64_t cols, std::uint64_t bytes) {
    const std::uint64_t n = rows * cols;  // both < 2^32: no overflow
    if (rows > limits_.max_elements || cols > limits_.max_elements || n > limits_.max_elements)
      damaged(std::string(what) + " declares " + std::to_string(rows) + " x " +
              std::to_string(cols) + " elements (limit " + std::to_string(limits_.max_elements) +
              ")");
    skip(n * bytes);
  }

  [[noreturn]] void damaged(const std::string& msg) const {
    throw ObjectDamaged(msg + " in " + where());
  }
  std::string where() const {
    return (cls_.empty() ? std::string("an object") : cls_) + " (byte " + std::to_string(off_) +
           " of the object)";
  }

  std::uint64_t offset() const { return off_; }
  const ObjectLimits& limits() const { return limits_; }
  std::string cls_;  ///< the innermost class being walked

 private:
  LookaheadStream& in_;
  const ObjectLimits& limits_;
  std::uint64_t off_ = 0;
};

bool walkObject(Cursor& c);

/// MRPT's class lookup (mrpt::rtti::findRegisteredClass) falls back to the name without its
/// namespace, so "garbage::CPose3D" is read as a CPose3D, and the name ends at a NUL byte: the
/// walk resolves names the same way.
std::string shortName(const std::string& cls) {
  const auto p = cls.rfind("::");
  return p == std::string::npos ? cls : cls.substr(p + 2);
}

/// Reads an object header; returns false for the legacy header, an over-long name or "nullptr"
/// (MRPT's own checks apply); sets the class's short name and version.
bool readHeader(Cursor& c, std::string& cls, std::uint8_t& version) {
  const std::uint8_t head = c.u8();
  if (!(head & 0x80)) return false;  // pre-0.5.5 header
  const unsigned len = head & 0x7F;
  if (len > 120) return false;  // MRPT refuses it with a message
  const std::uint8_t* name = c.take(len);
  // MRPT copies the name into a C string: a NUL ends it.
  const std::string full(reinterpret_cast<const char*>(name),
                         std::find(name, name + len, 0) - name);
  if (full == "nullptr") return false;
  cls = shortName(full);
  c.cls_ = full;  // for messages: damaged names may hold any byte
  for (char& ch : c.cls_)
    if (ch < 0x20 || ch > 0x7E) ch = '?';
  version = c.u8();
  return true;
}

void endFlag(Cursor& c) {
  const std::uint8_t end = c.u8();
  if (end != kEndFlag)
    c.damaged("the end-of-object flag is " + std::to_string(end) +
              ", not 136 (0x88): a size or field before it is wrong");
}

bool walkBody(Cursor& c, const std::string& cls, std::uint8_t v);

/// Thrown when a member of an object written by an old MRPT has a version the walk does not know:
/// the walk stops there and MRPT reads the rest unchecked.
struct StopWalk {};

/// A member object of a checked object: it must be of the expected class and, when `strict` (the
/// container is of a version MRPT 2.x writes), of a version the container's MRPT could have
/// written; else the bytes are damaged (MRPT would read the rest of the object unchecked).
void walkMember(Cursor& c, const char* expected, bool strict = true) {
  const std::string outer = c.cls_;
  std::string cls;
  std::uint8_t v = 0;
  if (!readHeader(c, cls, v) || cls != expected)
    c.damaged(std::string("a member object that should be a ") + expected + " is not");
  if (!walkBody(c, cls, v)) {
    if (!strict) throw StopWalk{};
    c.damaged("version " + std::to_string(v) + " of " + expected + " cannot be inside this object");
  }
  endFlag(c);
  c.cls_ = outer;
}

bool walkMatrixF(Cursor& c, std::uint8_t v) {
  if (v != 0) return false;
  const std::uint32_t rows = c.u32(), cols = c.u32();
  c.matrix("a float matrix", rows, cols, 4);
  return true;
}

bool walkPose3D(Cursor& c, std::uint8_t v) {
  if (v == 2)
    c.skip(7 * 8);  // x y z + quaternion
  else if (v == 3)
    c.skip(12 * 8);  // x y z + 3x3 rotation
  else
    return false;
  return true;
}

bool walkPose2D(Cursor& c, std::uint8_t v) {
  if (v != 1) return false;
  c.skip(3 * 8);
  return true;
}

bool walkImage(Cursor& c, std::uint8_t v) {
  if (v < 6 || v > 9) return false;
  if (c.flag("CImage external-storage flag")) {
    c.string("CImage external file name");
    return true;
  }
  const auto limit = c.limits().max_image_bytes;
  if (!c.flag("CImage colour flag")) {
    const std::int32_t w = c.i32(), h = c.i32();
    c.i32();  // origin
    const std::int32_t bytes = c.i32();
    if (v >= 9) c.i32();  // depth
    if (w < 0 || h < 0 || bytes < 0 ||
        static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) > limit ||
        static_cast<std::uint64_t>(bytes) > limit)
      c.damaged("a grey CImage declares " + std::to_string(w) + " x " + std::to_string(h) +
                " pixels in " + std::to_string(bytes) + " bytes");
    if (c.flag("CImage zip flag")) c.damaged("a zip-compressed CImage (MRPT cannot read it)");
    c.skip(static_cast<std::uint64_t>(bytes));
    return true;
  }
  const std::int32_t w = c.i32(), h = c.i32();
  if (w >= 1 && h >= 1) {  // JPEG
    const std::uint32_t n = c.u32();
    if (n > limit || static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h) > limit)
      c.damaged("a colour CImage declares " + std::to_string(w) + " x " + std::to_string(h) +
                " pixels in " + std::to_string(n) + " JPEG bytes");
    c.skip(n);
  } else if (w < 0 && h < 0) {  // raw RGB
    const std::uint64_t px = static_cast<std::uint64_t>(-static_cast<std::int64_t>(w)) *
                             static_cast<std::uint64_t>(-static_cast<std::int64_t>(h));
    if (px * 3 > limit)
      c.damaged("a raw colour CImage declares " + std::to_string(-static_cast<std::int64_t>(w)) +
                " x " + std::to_string(-static_cast<std::int64_t>(h)) + " pixels");
    c.skip(px * 3);
  } else if (w < 0 || h < 0) {
    c.damaged("a colour CImage declares " + std::to_string(w) + " x " + std::to_string(h) +
              " pixels");
  }
  return true;
}

bool walkCamera(Cursor& c, std::uint8_t v) {
  if (v < 4 || v > 6) return false;
  c.skip(13 * 8);  // focal length, 8 distortion coefficients, fx fy cx cy
  c.skip(2 * 4);   // nrows ncols
  if (v >= 5) c.string("TCamera name");
  if (v >= 6) c.u8();  // distortion model
  return true;
}

bool walkOdometry(Cursor& c, std::uint8_t v) {
  if (v != 2) return false;
  walkMember(c, "CPose2D");
  c.string("sensor label");
  c.skip(8);  // timestamp
  if (c.flag("encoders flag")) c.skip(2 * 4);
  if (c.flag("velocities flag")) c.skip(3 * 8);
  return true;
}

bool walkPixelLabels(Cursor& c) {
  if (c.u8() != 1) return false;  // TPixelLabelInfo version: MRPT reports others
  const std::uint8_t bytes = c.u8();
  if (bytes < 1 || bytes > 8) c.damaged("pixel labels of " + std::to_string(bytes) + " bytes");
  const std::uint64_t stored = bytes == 1 ? 1 : bytes == 2 ? 2 : bytes <= 4 ? 4 : 8;
  const std::uint32_t rows = c.u32(), cols = c.u32();
  c.matrix("the pixel labels", rows, cols, stored);
  // std::map<uint32_t, std::string>: container name, key type, value type, count, entries
  c.string("label map preamble");
  c.string("label map key type");
  c.string("label map value type");
  const std::uint32_t n = c.u32();
  if (n > 64) c.damaged(std::to_string(n) + " label names (at most 64 labels)");
  for (std::uint32_t i = 0; i < n; i++) {
    c.skip(4);
    c.string("label name");
  }
  return true;
}

bool walkRangeScan3D(Cursor& c, std::uint8_t v) {
  if (v > 10) return false;
  const bool strict = v >= 9;  // members written by MRPT 2.x; older files: stop at what is unknown
  c.skip(4);                   // maxRange
  walkMember(c, "CPose3D", strict);
  if (v == 0 || c.flag("hasPoints3D")) {
    const std::uint32_t n = c.u32();
    // x y z floats; v0 one validity byte per point; v8+ two uint16 pixel indices
    c.matrix("points3D", n, 1, v == 0 ? 3 * 4 + 1 : v >= 8 ? 3 * 4 + 2 * 2 : 3 * 4);
  }
  if (v >= 1) {
    const bool range = c.flag("hasRangeImage");
    if (v >= 9) c.skip(4);  // rangeUnits
    if (range) {
      if (v < 9) {
        walkMember(c, "CMatrixF", false);
      } else {
        const std::uint32_t rows = c.u32(), cols = c.u32();
        c.matrix("the range image", rows, cols, 2);
      }
    }
    if (c.flag("hasIntensityImage")) walkMember(c, "CImage", strict);
    if (c.flag("hasConfidenceImage")) walkMember(c, "CImage", strict);
    if (v >= 2) walkMember(c, "TCamera", strict);
    if (v >= 4) {
      walkMember(c, "TCamera", strict);
      walkMember(c, "CPose3D", strict);
    }
  }
  c.skip(4 + 8);  // stdError, timestamp
  c.string("sensor label");
  if (v >= 3) {
    c.flag("points3D external flag");
    c.string("points3D external file");
    c.flag("range image external flag");
    c.string("range image external file");
  }
  if (v >= 5) c.flag("range_is_depth");
  if (v >= 6) c.u8();  // intensity channel
  if (v >= 7 && c.flag("pixel labels flag") && !walkPixelLabels(c))
    c.damaged("pixel labels of an unknown version");
  if (v >= 10) {
    const std::uint8_t layers = c.u8();
    for (unsigned i = 0; i < layers; i++) {
      c.string("range layer name");
      const std::uint32_t rows = c.u32(), cols = c.u32();
      c.matrix("a range image layer", rows, cols, 2);
    }
  }
  return true;
}

bool walkSensoryFrame(Cursor& c, std::uint8_t v) {
  if (v > 2) return false;
  if (v < 2) c.skip(4);   // frame ID
  if (v == 0) c.skip(8);  // timestamp
  const std::uint32_t n = c.u32();
  if (n > c.limits().max_observations)
    c.damaged("a sensory frame of " + std::to_string(n) + " observations");
  const std::string outer = c.cls_;
  for (std::uint32_t i = 0; i < n; i++) {
    if (!walkObject(c)) return false;
    c.cls_ = outer;
  }
  return true;
}

/// The count of a CActionCollection (its actions are not walked: MRPT reads them unchecked).
bool walkActions(Cursor& c, std::uint8_t v) {
  if (v != 0) return false;
  const std::uint32_t n = c.u32();
  if (n > c.limits().max_observations)
    c.damaged("an action collection of " + std::to_string(n) + " actions");
  return n == 0;  // an empty collection is walked completely
}

bool walkBody(Cursor& c, const std::string& cls, std::uint8_t v) {
  if (cls == "CObservation3DRangeScan") return walkRangeScan3D(c, v);
  if (cls == "CActionCollection") return walkActions(c, v);
  if (cls == "CSensoryFrame") return walkSensoryFrame(c, v);
  if (cls == "CObservationOdometry") return walkOdometry(c, v);
  if (cls == "CPose3D") return walkPose3D(c, v);
  if (cls == "CPose2D") return walkPose2D(c, v);
  if (cls == "CImage") return walkImage(c, v);
  if (cls == "TCamera") return walkCamera(c, v);
  if (cls == "CMatrixF") return walkMatrixF(c, v);
  return false;
}

/// A top-level object or one inside a sensory frame: header, body, end flag. False when the
/// walk cannot go on (a class it does not know, a version it does not know, the legacy header,
/// a null object): MRPT reads the rest unchecked.
bool walkObject(Cursor& c) {
  std::string cls;
  std::uint8_t v = 0;
  try {
    if (!readHeader(c, cls, v) || !walkBody(c, cls, v)) return false;
  } catch (const StopWalk&) {
    return false;
  }
  endFlag(c);
  return true;
}

}  // namespace

std::size_t checkNextObject(LookaheadStream& in, const ObjectLimits& limits) {
  if (in.ensure(1) == 0) return 0;
  Cursor c(in, limits);
  walkObject(c);
  return static_cast<std::size_t>(c.offset());
}

}  // namespace dynobj::mrptio::detail
