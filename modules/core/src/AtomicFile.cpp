// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/AtomicFile.h"

#include <cstdio>
#include <stdexcept>

namespace dynobj::core {

std::string partialName(const std::string& path) {
  return path + ".partial";
}

void commitPartial(const std::string& path) {
  const std::string partial = partialName(path);
  if (std::rename(partial.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + partial + "' to '" + path + "'");
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)), partial_(partialName(path_)) {
  out_.open(partial_, std::ios::binary | std::ios::trunc);
  if (!out_) throw std::runtime_error("cannot write '" + partial_ + "'");
}

AtomicFile::~AtomicFile() {
  if (committed_) return;
  out_.close();
  std::remove(partial_.c_str());
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
}

}  // namespace dynobj::core
