// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogReader.h"

#include <dynobj/io/CrashGuard.h>
#include <mrpt/io/CStream.h>
#include <mrpt/system/filesystem.h>

#include <algorithm>
#include <filesystem>

#include "SerializedObjectCheck.h"
#include "dynobj/mrptio/GzipStream.h"

namespace dynobj::mrptio {

namespace mobs = mrpt::obs;

namespace {

/// MRPT exception texts carry a call stack: keep the messages, drop the backtrace.
std::string firstLines(const std::string& msg) {
  std::string out;
  std::size_t start = 0;
  while (start < msg.size()) {
    const std::size_t end = std::min(msg.find('\n', start), msg.size());
    const std::string line = msg.substr(start, end - start);
    start = end + 1;
    if (line.rfind("Message:", 0) == 0) out += (out.empty() ? "" : " / ") + line.substr(9);
  }
  return out.empty() ? msg : out;
}

}  // namespace

std::vector<mobs::CObservation::Ptr> RawlogEntry::observations() const {
  if (observation) return {observation};
  std::vector<mobs::CObservation::Ptr> out;
  if (sensory_frame)
    for (const auto& o : *sensory_frame) out.push_back(o);
  return out;
}

struct RawlogReader::Input {
  explicit Input(std::unique_ptr<mrpt::io::CStream> source)
      : stream(std::move(source)), archive(mrpt::serialization::archiveUniquePtrFrom(stream)) {}
  detail::LookaheadStream stream;
  std::unique_ptr<mrpt::serialization::CArchive> archive;
};

RawlogReader::RawlogReader(const std::string& path) : path_(path) {
  if (std::filesystem::is_directory(path))
    throw RawlogError("'" + path +
                      "' is a folder, not a rawlog (a folder of .pcd / .bin sweeps: make a rawlog "
                      "of it with dynobj-import)");
  if (!mrpt::system::fileExists(path)) throw RawlogError("rawlog '" + path + "' does not exist");
  if (mrpt::system::getFileSize(path) == 0) throw RawlogError("rawlog '" + path + "' is empty");
  auto file = std::make_unique<GzipInputStream>();  // gzip (one or several members) or plain
  std::string err;
  if (!file->open(path, err))
    throw RawlogError("cannot open rawlog '" + path + "'" + (err.empty() ? "" : ": " + err));
  file_ = file.get();
  in_ = std::make_unique<Input>(std::move(file));
  io::setCrashInput(path_);
}

RawlogReader::RawlogReader(std::unique_ptr<mrpt::io::CStream> stream, const std::string& name)
    : path_(name), in_(std::make_unique<Input>(std::move(stream))) {}

double RawlogReader::fileFraction() const {
  if (!file_ || file_->getTotalBytesCount() == 0) return -1;
  return static_cast<double>(file_->fileBytesRead()) /
         static_cast<double>(file_->getTotalBytesCount());
}

RawlogReader::~RawlogReader() = default;

std::uint64_t RawlogReader::position() const {
  return in_->stream.getPosition();
}

mrpt::serialization::CSerializable::Ptr RawlogReader::readObject(const char* what) {
  const std::uint64_t before = position();
  io::setCrashPosition(entries_, before);
  const auto fail = [&](bool truncated, const std::string& msg) {
    return RawlogError("rawlog '" + path_ + "' is " + (truncated ? "truncated" : "damaged") +
                       " at entry " + std::to_string(entries_) + " (" + what + ", byte " +
                       std::to_string(before) + "): " + msg);
  };
  try {
    // Sizes first (MRPT would trust them), then MRPT reads the checked bytes.
    if (detail::checkNextObject(in_->stream) == 0) return nullptr;  // clean end of file
    return in_->archive->ReadObject();
  } catch (const detail::ObjectTruncated& e) {
    throw fail(true, e.what());
  } catch (const detail::ObjectDamaged& e) {
    throw fail(false, e.what());
  } catch (const mrpt::serialization::CExceptionEOF&) {
    if (position() == before) return nullptr;  // nothing of a new object was read
    throw RawlogError("rawlog '" + path_ + "' is truncated: entry " + std::to_string(entries_) +
                      " (" + what + ") ends early at byte " + std::to_string(position()));
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    // The object failed to parse: was it cut short by the end of the file?
    bool eof = msg.find("EOF") != std::string::npos;
    try {
      eof = eof || in_->stream.ensure(1) == 0;
    } catch (const std::exception&) {  // the gzip data is corrupt too
    }
    throw fail(eof, firstLines(msg));
  }
}

bool RawlogReader::next(RawlogEntry& entry) {
  entry = RawlogEntry{};
  entry.index = entries_;
  auto obj = readObject("object");
  if (!obj) return false;
  if (auto obs = std::dynamic_pointer_cast<mobs::CObservation>(obj)) {
    entry.observation = obs;
  } else if (auto acts = std::dynamic_pointer_cast<mobs::CActionCollection>(obj)) {
    auto sf_obj = readObject("sensory frame after an action collection");
    auto sf = std::dynamic_pointer_cast<mobs::CSensoryFrame>(sf_obj);
    if (!sf)
      throw RawlogError("rawlog '" + path_ + "' entry " + std::to_string(entries_) +
                        ": an action collection is not followed by a sensory frame" +
                        (sf_obj
                             ? std::string(" (found ") + sf_obj->GetRuntimeClass()->className + ")"
                             : std::string(" (end of file)")));
    entry.actions = acts;
    entry.sensory_frame = sf;
  } else if (auto sf = std::dynamic_pointer_cast<mobs::CSensoryFrame>(obj)) {
    entry.sensory_frame = sf;  // a frame without actions: accepted, as MRPT does
  } else {
    throw RawlogError("rawlog '" + path_ + "' entry " + std::to_string(entries_) +
                      ": unexpected object of class " + obj->GetRuntimeClass()->className);
  }
  entries_++;
  return true;
}

}  // namespace dynobj::mrptio
