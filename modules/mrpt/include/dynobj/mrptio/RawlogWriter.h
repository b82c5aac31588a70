// SPDX-License-Identifier: BSD-3-Clause
// The output rawlog of every tool (rawlog-dynobj, dynobj-import, the simulator): written to
// "<path>.partial" (io::PartialPath), renamed by commit(), removed when destroyed uncommitted.
#pragma once

#include <dynobj/io/AtomicFile.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/serialization/CSerializable.h>

#include <string>

namespace dynobj::mrptio {

class RawlogWriter {
 public:
  /// `compress_level`: gzip level (1 = fastest, MRPT's default; 9 = best; 0 = none). Throws naming
  /// the file.
  explicit RawlogWriter(const std::string& path, int compress_level = 1);
  ~RawlogWriter();
  RawlogWriter(const RawlogWriter&) = delete;
  RawlogWriter& operator=(const RawlogWriter&) = delete;

  /// Appends one object (an observation, a sensory frame, an action collection).
  void write(const mrpt::serialization::CSerializable& obj);
  /// Closes and renames into place. Throws std::runtime_error on failure.
  void commit();

  const std::string& path() const { return file_.path(); }

 private:
  io::PartialPath file_;
  mrpt::io::CFileGZOutputStream out_;
};

}  // namespace dynobj::mrptio
