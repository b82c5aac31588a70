// SPDX-License-Identifier: BSD-3-Clause
// A folder of sweeps, one file each (*.pcd or *.bin, KITTI-style), with optional time stamps
// from a text file (KITTI's times.txt / timestamps.txt).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynobj/io/CloudFile.h"
#include "dynobj/io/FormatError.h"

namespace dynobj::io {

/// a < b with digit runs compared by value ("2" < "10"), then plain order as a tie-break: the
/// order of sweep files named by number.
bool naturalLess(const std::string& a, const std::string& b);

class CloudFolder {
 public:
  /// Lists the *.pcd or *.bin files of `dir` (one format only) in natural name order (digit runs
  /// compare as numbers: 2.pcd before 10.pcd), taken as time order. `times_file` (optional) gives
  /// one stamp per sweep, a line each ('#' comments and blank lines skipped), strictly increasing:
  ///   "2011-09-26 13:02:25.964389445"  date and time, UTC (KITTI raw timestamps.txt) -> epoch ns
  ///   "1.036602e-01", "12.5"            seconds (anything with '.' or an exponent; KITTI
  ///   times.txt) "1317354879123456789"             an integer: nanoseconds
  /// Throws FormatError for a missing or empty folder, both formats, a bad times line
  /// ("<times>:<line>: ..."), or a stamp count different from the sweep count.
  explicit CloudFolder(const std::string& dir, const std::string& times_file = "");

  std::size_t size() const { return files_.size(); }
  const std::string& path(std::size_t k) const { return files_.at(k); }
  /// ".pcd" or ".bin".
  const std::string& extension() const { return ext_; }
  /// True when the stamps come from a times file.
  bool hasTimes() const { return !times_ns_.empty(); }
  /// Sweep k's stamp: from the times file, else k * periodNs() (default 100 ms = 10 Hz, from 0).
  std::int64_t timestampNs(std::size_t k) const;
  std::int64_t periodNs() const { return period_ns_; }
  /// The sweep period used without a times file. Throws std::invalid_argument unless > 0.
  void setPeriodNs(std::int64_t period_ns);
  /// Reads sweep k (readPcd or readKittiBin). Throws std::out_of_range, FormatError.
  CloudFile read(std::size_t k) const;

 private:
  std::string dir_, ext_;
  std::vector<std::string> files_;
  std::vector<std::int64_t> times_ns_;
  std::int64_t period_ns_ = 100000000;
};

}  // namespace dynobj::io
