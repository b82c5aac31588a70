// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/GzipStream.h"

#include <isa-l/igzip_lib.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>

namespace dynobj::mrptio {

namespace {

constexpr std::size_t kInBytes = 1u << 20;   // compressed bytes read at once
constexpr std::size_t kOutBytes = 1u << 18;  // decompressed buffer for small reads

std::size_t levelBufferSize(int level) {
  switch (level) {
    case 1:
      return ISAL_DEF_LVL1_DEFAULT;
    case 2:
      return ISAL_DEF_LVL2_DEFAULT;
    case 3:
      return ISAL_DEF_LVL3_DEFAULT;
    default:
      return 0;
  }
}

}  // namespace

GzipMemberEncoder::GzipMemberEncoder(int level) : level_(level) {
  if (level < 0 || level > kMaxLevel)
    throw std::invalid_argument("compression level must be 0..3 (0 = plain rawlog), got " +
                                std::to_string(level));
  level_buf_.resize(levelBufferSize(level));
}

GzipMemberEncoder::~GzipMemberEncoder() = default;

void GzipMemberEncoder::encode(const std::string& raw, std::string& out) {
  if (level_ == 0) {
    out = raw;
    return;
  }
  isal_zstream s;
  isal_deflate_stateless_init(&s);
  s.level = static_cast<std::uint32_t>(level_);
  s.level_buf = level_buf_.data();
  s.level_buf_size = static_cast<std::uint32_t>(level_buf_.size());
  s.gzip_flag = IGZIP_GZIP;
  s.end_of_stream = 1;
  s.flush = NO_FLUSH;
  // Worst case: stored blocks (5 bytes each per 64 kB) plus the gzip header and trailer.
  out.resize(raw.size() + raw.size() / 1024 + 1024);
  s.next_in = reinterpret_cast<std::uint8_t*>(const_cast<char*>(raw.data()));
  s.avail_in = static_cast<std::uint32_t>(raw.size());
  s.next_out = reinterpret_cast<std::uint8_t*>(out.data());
  s.avail_out = static_cast<std::uint32_t>(out.size());
  const int r = isal_deflate_stateless(&s);
  if (r != COMP_OK)
    throw std::runtime_error("gzip compression failed (ISA-L error " + std::to_string(r) + ")");
  out.resize(s.total_out);
}

struct GzipInputStream::State {
  inflate_state st;
};

GzipInputStream::GzipInputStream() : state_(std::make_unique<State>()) {}

GzipInputStream::~GzipInputStream() {
  if (file_) std::fclose(file_);
}

bool GzipInputStream::open(const std::string& path, std::string& error) {
  path_ = path;
  file_ = std::fopen(path.c_str(), "rb");
  if (!file_) {
    error = std::strerror(errno);
    return false;
  }
  std::fseek(file_, 0, SEEK_END);
  file_size_ = static_cast<std::uint64_t>(std::ftell(file_));
  std::fseek(file_, 0, SEEK_SET);
  in_.resize(kInBytes);
  out_.resize(kOutBytes);
  fill();
  gzip_ = in_end_ >= 2 && in_[0] == 0x1f && in_[1] == 0x8b;
  if (gzip_) {
    isal_inflate_init(&state_->st);
    state_->st.crc_flag = ISAL_GZIP;
  }
  return true;
}

bool GzipInputStream::fill() {
  if (in_start_ > 0) {  // keep what is left at the front
    std::memmove(in_.data(), in_.data() + in_start_, in_end_ - in_start_);
    in_end_ -= in_start_;
    in_start_ = 0;
  }
  if (in_end_ == in_.size() || !file_) return false;
  const std::size_t n = std::fread(in_.data() + in_end_, 1, in_.size() - in_end_, file_);
  in_end_ += n;
  consumed_ += n;
  return n > 0;
}

size_t GzipInputStream::Read(void* buffer, size_t count) {
  auto* dst = static_cast<std::uint8_t*>(buffer);
  std::size_t done = 0;
  while (done < count) {
    if (out_start_ < out_end_) {
      const std::size_t n = std::min(count - done, out_end_ - out_start_);
      std::memcpy(dst + done, out_.data() + out_start_, n);
      out_start_ += n;
      done += n;
      continue;
    }
    if (eof_ || failed_) break;
    if (count - done >= out_.size()) {  // large reads (a scan's arrays): straight into `buffer`
      const std::size_t n = inflateInto(dst + done, count - done);
      if (n == 0) break;
      done += n;
    } else {
      out_start_ = 0;
      out_end_ = inflateInto(out_.data(), out_.size());
      if (out_end_ == 0) break;
    }
  }
  position_ += done;
  return done;
}

std::size_t GzipInputStream::inflateInto(std::uint8_t* dst, std::size_t cap) {
  if (!gzip_) {  // a plain file: what is buffered, then straight from the file
    std::size_t n = std::min(cap, in_end_ - in_start_);
    std::memcpy(dst, in_.data() + in_start_, n);
    in_start_ += n;
    if (n == 0) n = std::fread(dst, 1, cap, file_);
    if (n == 0) eof_ = true;
    return n;
  }
  inflate_state& st = state_->st;
  for (;;) {
    if (member_done_) {  // another member, trailing garbage (ignored, as zlib does) or the end
      if (in_end_ - in_start_ < 2) fill();
      if (in_end_ - in_start_ < 2 || in_[in_start_] != 0x1f || in_[in_start_ + 1] != 0x8b) {
        eof_ = true;
        return 0;
      }
      isal_inflate_reset(&st);
      st.crc_flag = ISAL_GZIP;
      member_done_ = false;
    }
    if (in_start_ == in_end_ && !fill()) {  // the file ends inside a member: truncated
      eof_ = true;
      return 0;
    }
    st.next_in = in_.data() + in_start_;
    st.avail_in = static_cast<std::uint32_t>(in_end_ - in_start_);
    st.next_out = dst;
    st.avail_out = static_cast<std::uint32_t>(std::min<std::size_t>(cap, 1u << 30));
    const int r = isal_inflate(&st);
    in_start_ = in_end_ - st.avail_in;
    const std::size_t n = static_cast<std::size_t>(st.next_out - dst);
    if (r < 0) {
      failed_ = true;
      throw std::runtime_error("damaged gzip data in '" + path_ + "' (ISA-L inflate error " +
                               std::to_string(r) + ", near compressed byte " +
                               std::to_string(consumed_ - (in_end_ - in_start_)) + ")");
    }
    if (st.block_state == ISAL_BLOCK_FINISH) member_done_ = true;
    if (n > 0) return n;
  }
}

size_t GzipInputStream::Write(const void*, size_t) {
  throw std::logic_error("GzipInputStream is read-only");
}

uint64_t GzipInputStream::Seek(int64_t, CStream::TSeekOrigin) {
  throw std::logic_error("GzipInputStream cannot seek");
}

uint64_t GzipInputStream::getTotalBytesCount() const {
  return file_size_;
}

uint64_t GzipInputStream::getPosition() const {
  return position_;
}

}  // namespace dynobj::mrptio
