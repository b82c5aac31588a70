// SPDX-License-Identifier: BSD-3-Clause
// Output files that are either complete or absent: everything is written to "<path>.partial" and
// renamed to <path> only by commit(); an uncommitted file (an error, an exception) is removed.
// Every writer of the project goes through it (label files, simulator output, reports, maps).
#pragma once

#include <fstream>
#include <string>

namespace dynobj::core {

class AtomicFile {
 public:
  /// Opens "<path>.partial" for writing (binary). Throws std::runtime_error naming it on failure.
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ofstream& stream() { return out_; }
  const std::string& path() const { return path_; }
  const std::string& partialPath() const { return partial_; }
  /// Flushes, checks the stream, renames into place. Throws std::runtime_error on an I/O error.
  void commit();

 private:
  std::string path_, partial_;
  std::ofstream out_;
  bool committed_ = false;
};

/// For files written by other libraries: renames "<path>.partial" to <path>, throwing on failure.
void commitPartial(const std::string& path);
/// "<path>.partial".
std::string partialName(const std::string& path);
/// Writes `content` through an AtomicFile in one go.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace dynobj::core
