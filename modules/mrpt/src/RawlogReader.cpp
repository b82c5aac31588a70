// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogReader.h"

#include <mrpt/system/filesystem.h>

#include <algorithm>

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

RawlogReader::RawlogReader(const std::string& path) : path_(path) {
  if (!mrpt::system::fileExists(path)) throw RawlogError("rawlog '" + path + "' does not exist");
  if (mrpt::system::getFileSize(path) == 0) throw RawlogError("rawlog '" + path + "' is empty");
  std::string err;
  if (!in_.open(path, err))
    throw RawlogError("cannot open rawlog '" + path + "'" + (err.empty() ? "" : ": " + err));
  archive_ = mrpt::serialization::archiveUniquePtrFrom(in_);
}

mrpt::serialization::CSerializable::Ptr RawlogReader::readObject(const char* what) {
  const std::uint64_t before = in_.getPosition();
  try {
    return archive_->ReadObject();
  } catch (const mrpt::serialization::CExceptionEOF&) {
    if (in_.getPosition() == before) return nullptr;  // nothing of a new object was read
    throw RawlogError("rawlog '" + path_ + "' is truncated: entry " + std::to_string(entries_) +
                      " (" + what + ") ends early at byte " + std::to_string(in_.getPosition()));
  } catch (const std::exception& e) {
    const std::string msg = e.what();
    char probe = 0;  // the object failed to parse: was it cut short by the end of the file?
    const bool eof = msg.find("EOF") != std::string::npos || in_.Read(&probe, 1) == 0;
    throw RawlogError("rawlog '" + path_ + "' is " + (eof ? "truncated" : "damaged") +
                      " at entry " + std::to_string(entries_) + " (" + what + ", byte " +
                      std::to_string(before) + "): " + firstLines(msg));
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
