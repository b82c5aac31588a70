// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogIndex.h"

#include <mrpt/io/CStream.h>
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt/serialization/CArchive.h>
#include <zlib.h>

#include <filesystem>
#include <stdexcept>

#include "dynobj/mrptio/PoseConversion.h"
#include "dynobj/mrptio/RawlogReader.h"
#include "dynobj/mrptio/TimeConversion.h"

namespace dynobj::mrptio {

namespace mobs = mrpt::obs;

/// A read-only MRPT stream over zlib's gzFile, which reads plain files too and can seek
/// (CFileGZInputStream cannot).
class RawlogIndex::Stream : public mrpt::io::CStream {
 public:
  explicit Stream(const std::string& path) : path_(path) {
    f_ = gzopen(path.c_str(), "rb");
    if (!f_) throw RawlogError("cannot open rawlog '" + path + "'");
    gzbuffer(f_, 1 << 18);
  }
  ~Stream() override {
    if (f_) gzclose(f_);
  }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;

  size_t Read(void* buf, size_t n) override {
    auto* out = static_cast<char*>(buf);
    size_t done = 0;
    while (done < n) {
      const unsigned chunk = static_cast<unsigned>(std::min<size_t>(n - done, 1u << 30));
      const int got = gzread(f_, out + done, chunk);
      if (got < 0) {
        int err = 0;
        throw RawlogError("rawlog '" + path_ + "' is damaged (compressed data): " +
                          gzerror(f_, &err));
      }
      if (got == 0) break;
      done += static_cast<size_t>(got);
    }
    return done;
  }
  size_t Write(const void*, size_t) override {
    throw std::logic_error("RawlogIndex: the input is never written");
  }
  uint64_t Seek(int64_t off, CStream::TSeekOrigin origin) override {
    const int whence = origin == sFromBeginning ? SEEK_SET : SEEK_CUR;
    if (origin == sFromEnd) throw std::logic_error("RawlogIndex: cannot seek from the end");
    const z_off_t r = gzseek(f_, static_cast<z_off_t>(off), whence);
    if (r < 0) throw RawlogError("rawlog '" + path_ + "': cannot seek to byte " + std::to_string(off));
    return static_cast<uint64_t>(r);
  }
  uint64_t getTotalBytesCount() const override { return 0; }
  uint64_t getPosition() const override { return static_cast<uint64_t>(gztell(f_)); }
  /// Compressed bytes consumed (for progress).
  uint64_t rawPosition() const { return static_cast<uint64_t>(gzoffset(f_)); }

 private:
  std::string path_;
  gzFile f_ = nullptr;
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
  in_ = std::make_unique<Stream>(path_);
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
    throw RawlogError("rawlog '" + path_ + "' has no LiDAR observation" +
                      (opts.sensor_label.empty() ? std::string()
                                                 : " with label '" + opts.sensor_label + "'"));
}

RawlogIndex::~RawlogIndex() = default;

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
