// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogIndex.h"

#include <mrpt/io/CStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <zlib.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "dynobj/mrptio/PoseConversion.h"
#include "dynobj/mrptio/RawlogReader.h"
#include "dynobj/mrptio/TimeConversion.h"

namespace dynobj::mrptio {

namespace mobs = mrpt::obs;

/// A read-only MRPT stream over a plain or gzip file that can seek both ways. gzip cannot be
/// entered in the middle, so while reading forward it keeps a copy of the decompressor's state
/// (zlib's inflateCopy: ~40 kB) every `every` bytes of output; a seek restarts from the
/// nearest earlier copy, so it costs at most that much decompression (CFileGZInputStream
/// cannot seek at all, and zlib's gzseek restarts backward seeks from the file's start).
class RawlogIndex::Stream : public mrpt::io::CStream {
 public:
  Stream(const std::string& path, std::uint64_t every)
      : path_(path), in_(1 << 18), every_(std::max<std::uint64_t>(every, 1 << 16)) {
    f_ = std::fopen(path.c_str(), "rb");
    if (!f_) throw RawlogError("cannot open rawlog '" + path + "': " + std::strerror(errno));
    unsigned char magic[2] = {0, 0};
    gz_ = std::fread(magic, 1, 2, f_) == 2 && magic[0] == 0x1f && magic[1] == 0x8b;
    std::fseek(f_, 0, SEEK_SET);
    if (gz_) {
      if (inflateInit2(&zs_, 16 + MAX_WBITS) != Z_OK)
        throw RawlogError("rawlog '" + path + "': cannot start zlib");
      checkpoint();
    }
  }
  ~Stream() override {
    if (gz_) inflateEnd(&zs_);
    for (auto& c : cps_) inflateEnd(c.zs.get());
    if (f_) std::fclose(f_);
  }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;

  size_t Read(void* buf, size_t n) override {
    if (!gz_) {
      const size_t got = std::fread(buf, 1, n, f_);
      pos_ += got;
      file_pos_ += got;
      return got;
    }
    auto* out = static_cast<unsigned char*>(buf);
    size_t done = 0;
    while (done < n) {
      if (zs_.avail_in == 0 && !eof_ && !refill()) eof_ = true;
      if (pos_ >= cps_.back().out + every_) checkpoint();
      const size_t want = std::min<size_t>(n - done, 1u << 30);
      zs_.next_out = out + done;
      zs_.avail_out = static_cast<uInt>(want);
      const int ret = inflate(&zs_, Z_NO_FLUSH);  // also with no input: it may hold output
      const size_t got = want - zs_.avail_out;
      done += got;
      pos_ += got;
      if (ret == Z_STREAM_END) {  // a gzip member ends: another may follow
        if (zs_.avail_in == 0 && !eof_ && !refill()) eof_ = true;
        if (zs_.avail_in == 0) break;  // the end of the file
        inflateReset(&zs_);
        continue;
      }
      if (ret == Z_BUF_ERROR && zs_.avail_in == 0) {
        if (eof_) break;  // cut short: the caller sees a short read ("truncated")
        continue;
      }
      if (ret != Z_OK)
        throw RawlogError("rawlog '" + path_ + "' is damaged (compressed data: " +
                          (zs_.msg ? zs_.msg : "zlib error " + std::to_string(ret)) + ")");
    }
    return done;
  }
  size_t Write(const void*, size_t) override {
    throw std::logic_error("RawlogIndex: the input is never written");
  }
  uint64_t Seek(int64_t off, CStream::TSeekOrigin origin) override {
    if (origin != sFromBeginning) throw std::logic_error("RawlogIndex: absolute seeks only");
    const auto target = static_cast<std::uint64_t>(off);
    if (!gz_) {
      if (std::fseek(f_, static_cast<long>(off), SEEK_SET) != 0)
        throw RawlogError("rawlog '" + path_ + "': cannot seek to byte " + std::to_string(off));
      pos_ = file_pos_ = target;
      return pos_;
    }
    const Checkpoint* best = &cps_.front();
    for (const auto& c : cps_)
      if (c.out <= target) best = &c;
    if (!(pos_ <= target && pos_ >= best->out)) {  // restart from the copy
      inflateEnd(&zs_);
      if (inflateCopy(&zs_, best->zs.get()) != Z_OK)
        throw RawlogError("rawlog '" + path_ + "': cannot restore the zlib state");
      std::fseek(f_, static_cast<long>(best->in), SEEK_SET);
      file_pos_ = best->in;
      zs_.avail_in = 0;
      zs_.next_in = in_.data();
      eof_ = false;
      pos_ = best->out;
    }
    std::vector<char> skip(1 << 16);
    while (pos_ < target) {
      const size_t got = Read(skip.data(), std::min<std::uint64_t>(skip.size(), target - pos_));
      if (got == 0) throw RawlogError("rawlog '" + path_ + "' is shorter than when it was indexed");
    }
    return pos_;
  }
  uint64_t getTotalBytesCount() const override { return 0; }
  uint64_t getPosition() const override { return pos_; }
  /// File bytes consumed (for progress).
  uint64_t rawPosition() const { return file_pos_; }
  std::size_t checkpoints() const { return cps_.size(); }

 private:
  struct Checkpoint {
    std::uint64_t out = 0;  ///< uncompressed position
    std::uint64_t in = 0;   ///< file offset of the next compressed byte
    std::unique_ptr<z_stream> zs;
  };

  bool refill() {
    const size_t got = std::fread(in_.data(), 1, in_.size(), f_);
    file_pos_ += got;
    zs_.next_in = in_.data();
    zs_.avail_in = static_cast<uInt>(got);
    return got > 0;
  }
  void checkpoint() {
    Checkpoint c;
    c.out = pos_;
    c.in = file_pos_ - zs_.avail_in;
    c.zs = std::make_unique<z_stream>();
    if (inflateCopy(c.zs.get(), &zs_) != Z_OK)
      throw RawlogError("rawlog '" + path_ + "': cannot copy the zlib state");
    cps_.push_back(std::move(c));
  }

  std::string path_;
  std::FILE* f_ = nullptr;
  bool gz_ = false, eof_ = false;
  z_stream zs_{};
  std::vector<unsigned char> in_;
  std::uint64_t pos_ = 0, file_pos_ = 0;
  std::vector<Checkpoint> cps_;
  std::uint64_t every_;
};

namespace {

/// Reads one object; nullptr at a clean end of file. Throws RawlogError on a damaged file.
mrpt::serialization::CSerializable::Ptr readObject(mrpt::serialization::CArchive& ar,
                                                   mrpt::io::CStream& in, const std::string& path,
                                                   std::size_t entry) {
  const std::uint64_t before = in.getPosition();
  try {
    return ar.ReadObject();
  } catch (const mrpt::serialization::CExceptionEOF&) {
    if (in.getPosition() == before) return nullptr;
    throw RawlogError("rawlog '" + path + "' is truncated: entry " + std::to_string(entry) +
                      " ends early");
  } catch (const RawlogError&) {
    throw;
  } catch (const std::exception& e) {
    std::string msg = e.what();
    if (const auto p = msg.find("Message:"); p != std::string::npos) msg = msg.substr(p + 9);
    if (const auto p = msg.find('\n'); p != std::string::npos) msg = msg.substr(0, p);
    throw RawlogError("rawlog '" + path + "' is damaged at entry " + std::to_string(entry) +
                      " (byte " + std::to_string(before) + "): " + msg);
  }
}

/// The observations of the entry starting at the stream's position; empty at the end of file.
bool readEntry(mrpt::serialization::CArchive& ar, mrpt::io::CStream& in, const std::string& path,
               std::size_t entry, std::vector<mobs::CObservation::Ptr>& out) {
  out.clear();
  auto obj = readObject(ar, in, path, entry);
  if (!obj) return false;
  if (auto obs = std::dynamic_pointer_cast<mobs::CObservation>(obj)) {
    out.push_back(obs);
    return true;
  }
  if (std::dynamic_pointer_cast<mobs::CActionCollection>(obj)) {
    obj = readObject(ar, in, path, entry);
    if (!std::dynamic_pointer_cast<mobs::CSensoryFrame>(obj))
      throw RawlogError("rawlog '" + path + "' entry " + std::to_string(entry) +
                        ": an action collection is not followed by a sensory frame");
  }
  if (auto sf = std::dynamic_pointer_cast<mobs::CSensoryFrame>(obj)) {
    for (const auto& o : *sf) out.push_back(o);
    return true;
  }
  throw RawlogError("rawlog '" + path + "' entry " + std::to_string(entry) +
                    ": unexpected object of class " + obj->GetRuntimeClass()->className);
}

}  // namespace

RawlogIndex::RawlogIndex(std::string rawlog, ObservationConverter converter, Options opts)
    : path_(std::move(rawlog)), converter_(std::move(converter)), label_(opts.sensor_label) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path_, ec))
    throw RawlogError("rawlog '" + path_ + "' does not exist or is not a file");
  if (std::filesystem::file_size(path_, ec) == 0)
    throw RawlogError("rawlog '" + path_ + "' is empty");
  in_ = std::make_unique<Stream>(path_, opts.checkpoint_bytes);
  auto ar = mrpt::serialization::archiveFrom(*in_);
  std::vector<mobs::CObservation::Ptr> obs;
  std::optional<Eigen::Isometry3d> odometry;
  std::string other_label;
  for (;;) {
    const std::uint64_t offset = in_->getPosition();
    if (!readEntry(ar, *in_, path_, entries_, obs)) break;
    for (std::size_t i = 0; i < obs.size(); i++) {
      const auto& o = obs[i];
      if (!o) continue;
      if (const auto* odo = dynamic_cast<const mobs::CObservationOdometry*>(o.get())) {
        odometry = toIsometry(mrpt::poses::CPose3D(odo->odometry));
        continue;
      }
      if (!ObservationConverter::isLidarObservation(*o)) continue;
      if (label_.empty()) label_ = o->sensorLabel;
      if (o->sensorLabel != label_) {
        if (opts.sensor_label.empty())
          throw RawlogError("rawlog '" + path_ + "' has several LiDARs ('" + label_ + "', '" +
                            o->sensorLabel + "'): choose one with --sensor-label");
        continue;
      }
      Sweep s;
      s.offset = offset;
      s.entry = entries_;
      s.in_entry = static_cast<std::uint32_t>(i);
      s.timestamp_ns = toUnixNs(o->timestamp);
      s.odometry = odometry;
      if (!sweeps_.empty() && s.timestamp_ns <= sweeps_.back().timestamp_ns)
        throw RawlogError("rawlog '" + path_ + "' entry " + std::to_string(entries_) +
                          ": the sweep's time is not after the previous sweep's (entry " +
                          std::to_string(sweeps_.back().entry) + ")");
      sweeps_.push_back(std::move(s));
    }
    entries_++;
    if (opts.progress && entries_ % 200 == 0) opts.progress(entries_, in_->rawPosition());
  }
  if (sweeps_.empty())
    throw RawlogError(
        "rawlog '" + path_ + "' has no LiDAR observation" +
        (opts.sensor_label.empty() ? std::string() : " with label '" + opts.sensor_label + "'"));
}

RawlogIndex::~RawlogIndex() = default;

std::size_t RawlogIndex::checkpoints() const {
  return in_->checkpoints();
}

void RawlogIndex::read(std::size_t k, Frame& f) {
  const Sweep& s = sweeps_.at(k);
  in_->Seek(static_cast<int64_t>(s.offset), mrpt::io::CStream::sFromBeginning);
  auto ar = mrpt::serialization::archiveFrom(*in_);
  std::vector<mobs::CObservation::Ptr> obs;
  if (!readEntry(ar, *in_, path_, s.entry, obs) || s.in_entry >= obs.size())
    throw RawlogError("rawlog '" + path_ + "' changed since it was opened (entry " +
                      std::to_string(s.entry) + ")");
  const auto& o = obs[s.in_entry];
  f.stats = converter_.convert(*o, f.frame);
  mrpt::poses::CPose3D mount;
  o->getSensorPose(mount);
  f.index = k;
  f.entry = s.entry;
  f.where = "'" + path_ + "' entry " + std::to_string(s.entry);
  f.sensor_label = o->sensorLabel;
  f.mount = toIsometry(mount);
  f.odometry = s.odometry;
  f.viewpoint.reset();
  f.observation = o;
}

}  // namespace dynobj::mrptio
