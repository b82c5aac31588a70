// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/AtomicFile.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "dynobj/io/CrashGuard.h"

namespace dynobj::io {
namespace {

void renameOrThrow(const std::string& from, const std::string& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + from + "' to '" + to + "'");
}

}  // namespace

std::string cannotWriteMessage(const std::string& path, int err) {
  namespace fs = std::filesystem;
  const fs::path parent = fs::path(path).parent_path();
  const std::string dir = parent.empty() ? "." : parent.string();
  std::error_code ec;
  std::string why;
  if (!fs::exists(dir, ec))
    why = "the folder '" + dir + "' does not exist";
  else if (!fs::is_directory(dir, ec))
    why = "'" + dir + "' is not a folder";
  else if (access(dir.c_str(), W_OK) != 0)
    why = "the folder '" + dir + "' is not writable";
  else if (fs::is_directory(path, ec))
    why = "it is a folder";
  else
    why = err ? std::strerror(err) : "unknown error";
  return "cannot write '" + path + "': " + why;
}

std::string partialName(const std::string& path) {
  return path + ".partial";
}

void commitPartial(const std::string& path) {
  renameOrThrow(partialName(path), path);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), partial_(partialName(path_)) {
  guard_ = registerPartialOutput(partial_);
  errno = 0;
  out_.open(partial_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    const int err = errno;
    unregisterPartialOutput(guard_);
    throw std::runtime_error(cannotWriteMessage(path_, err));
  }
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::remove(partial_.c_str());
  unregisterPartialOutput(guard_);
}

void writeFileAtomically(const std::string& path, const std::string& content) {
  AtomicFile f(path);
  f.stream() << content;
  f.commit();
}

void AtomicFile::commit() {
  out_.flush();
  out_.close();
  if (!out_) throw std::runtime_error("error writing '" + partial_ + "'");
  commitPartial(path_);
  committed_ = true;
  unregisterPartialOutput(guard_);
}

PartialPath::PartialPath(std::string path, const std::string& suffix)
    : path_(std::move(path)), partial_(partialName(path_) + suffix) {
  guard_ = registerPartialOutput(partial_);
}

PartialPath::~PartialPath() {
  if (committed_) return;
  std::error_code ec;
  std::filesystem::remove_all(partial_, ec);
  unregisterPartialOutput(guard_);
}

void PartialPath::commit() {
  renameOrThrow(partial_, path_);
  committed_ = true;
  unregisterPartialOutput(guard_);
}

}  // namespace dynobj::io
