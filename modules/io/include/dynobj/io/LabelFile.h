// SPDX-License-Identifier: BSD-3-Clause
// The dynamic-label file format v1 (docs/formats.md): per sweep, the pixels that are dynamic.
//   line 1:  # dynobj-labels v1 rows=<H> cols=<W>
//   then one line per sweep, in time order:  <timestamp_ns> <count> <idx> <idx> ...
//   with idx = row * W + col, strictly ascending; a sweep with no dynamic pixel has count 0.
// Ground truth (dynobj-sim) and detector output use the same format. Its instance variant
// (`# dynobj-instances v1 ...`, entries `<idx>:<object id>`) says which object each pixel hit.
// Files made by people (dynobj-label) add a second line `# reviewed <sweeps>` (0-based positions,
// ranges, e.g. `0-10,12`, or `none`): the sweeps a person checked. Without that line every sweep
// counts as reviewed (simulator ground truth).
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynobj/io/AtomicFile.h"

namespace dynobj::io {

/// A malformed label file; what() names the file and line.
class LabelFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct LabelSweep {
  std::int64_t timestamp_ns = 0;
  std::vector<std::uint32_t> pixels;  ///< row * cols + col, ascending
  std::vector<std::int32_t> ids;      ///< instance files only: the object of each pixel
};

struct LabelFile {
  int rows = 0, cols = 0;
  bool instances = false;  ///< an instance file (every pixel carries an object id)
  std::vector<LabelSweep> sweeps;
  /// The file has a `# reviewed` line; then reviewed[k] tells whether a person checked sweep k.
  bool has_review = false;
  std::vector<std::uint8_t> reviewed;

  bool isReviewed(std::size_t k) const {
    return !has_review || (k < reviewed.size() && reviewed[k]);
  }
  /// Positions of the sweeps nobody reviewed (none without a `# reviewed` line).
  std::vector<std::size_t> unreviewedSweeps() const;
  /// Throws LabelFileError naming `path`, how many sweeps are unreviewed and the first ones.
  void requireReviewed(const std::string& path) const;
  /// Drops the unreviewed sweeps (what is left is all reviewed).
  void keepReviewedOnly();

  /// Reads and checks a whole file (header, counts, index range, ascending order, increasing
  /// timestamps). Throws LabelFileError "<path>:<line>: <problem>".
  static LabelFile read(const std::string& path);
};

/// "0-10,12" for the set entries of `flags` ("none" when there is none); and back (throws
/// std::invalid_argument on a malformed list or a position >= n).
std::string formatSweepRanges(const std::vector<std::uint8_t>& flags);
std::vector<std::uint8_t> parseSweepRanges(const std::string& text, std::size_t n);

/// The non-zero pixels of a mask as ascending indices (row * cols + col).
std::vector<std::uint32_t> pixelsOfMask(const cv::Mat_<std::uint8_t>& mask);
/// The inverse: a rows x cols mask, 255 on the given pixels, 0 elsewhere.
cv::Mat_<std::uint8_t> maskOfPixels(const std::vector<std::uint32_t>& pixels, int rows, int cols);

/// Streams sweeps into `<path>.partial` and renames it to `path` on close(): a file at `path`
/// is always complete. Destroying an unclosed writer removes the partial file.
class LabelFileWriter {
 public:
  /// `instances`: write the instance variant (write() then takes one id per pixel).
  LabelFileWriter(const std::string& path, int rows, int cols, bool instances = false);
  LabelFileWriter(const LabelFileWriter&) = delete;
  LabelFileWriter& operator=(const LabelFileWriter&) = delete;

  /// Writes the `# reviewed` line (one flag per sweep that will follow); only before write().
  void writeReviewed(const std::vector<std::uint8_t>& reviewed);

  /// Appends one sweep; `pixels` must be ascending and inside the image, timestamps increasing.
  void write(std::int64_t timestamp_ns, const std::vector<std::uint32_t>& pixels,
             const std::vector<std::int32_t>& ids = {});
  /// Flushes, checks and renames into place. Throws std::runtime_error on an I/O failure.
  void close();

 private:
  AtomicFile file_;
  int rows_, cols_;
  bool instances_;
  bool any_ = false;
  std::int64_t last_ts_ = 0;
  std::size_t written_ = 0;
  std::int64_t review_count_ = -1;  ///< sweeps the '# reviewed' line promised (-1: no line)
};

}  // namespace dynobj::io
