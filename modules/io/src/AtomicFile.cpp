// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/AtomicFile.h"

#include <cstdio>
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

std::string partialName(const std::string& path) {
  return path + ".partial";
}

void commitPartial(const std::string& path) {
  renameOrThrow(partialName(path), path);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), partial_(partialName(path_)) {
  guard_ = registerPartialOutput(partial_);
  out_.open(partial_, std::ios::binary | std::ios::trunc);
  if (!out_) {
    unregisterPartialOutput(guard_);
    throw std::runtime_error("cannot write '" + partial_ + "'");
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
