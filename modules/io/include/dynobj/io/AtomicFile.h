// SPDX-License-Identifier: BSD-3-Clause
// The project's one mechanism for output files that are either complete or absent: everything is
// written to "<path>.partial" and renamed to <path> only by commit(); an uncommitted file (an
// error, an exception) is removed, and so is one left by a crash or a kill (CrashGuard.h).
// AtomicFile for files we write through a std::ofstream; PartialPath for files other libraries
// write by name (rawlogs, simplemaps, PNGs, folders).
#pragma once

#include <fstream>
#include <string>

namespace dynobj::io {

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
  int guard_ = -1;  ///< CrashGuard registration of partial_
};

/// A file (or folder) another library writes by name: write to partial(), then commit() renames
/// it to path(); destroyed uncommitted, it removes partial() (recursively for a folder).
class PartialPath {
 public:
  /// `suffix` is appended after ".partial" (e.g. ".png", so that OpenCV picks the codec).
  explicit PartialPath(std::string path, const std::string& suffix = "");
  ~PartialPath();
  PartialPath(const PartialPath&) = delete;
  PartialPath& operator=(const PartialPath&) = delete;

  const std::string& path() const { return path_; }
  const std::string& partial() const { return partial_; }
  /// Renames partial() to path(). Throws std::runtime_error naming both on failure.
  void commit();

 private:
  std::string path_, partial_;
  bool committed_ = false;
  int guard_ = -1;  ///< CrashGuard registration of partial_
};

/// "<path>.partial".
std::string partialName(const std::string& path);
/// Renames "<path>.partial" to <path>, throwing on failure.
void commitPartial(const std::string& path);
/// "cannot write '<path>': <why>", why naming the real cause: the folder that does not exist, a
/// path that is not a folder, a folder not writable, else `err` (an errno value) when set.
std::string cannotWriteMessage(const std::string& path, int err = 0);
/// Writes `content` through an AtomicFile in one go.
void writeFileAtomically(const std::string& path, const std::string& content);

}  // namespace dynobj::io
