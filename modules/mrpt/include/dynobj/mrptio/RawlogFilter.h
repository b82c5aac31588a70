// SPDX-License-Identifier: BSD-3-Clause
// rawlog-dynobj's job as a library call: rawlog in -> rawlog out, entry by entry (memory stays
// flat), every observation through a DynamicObjectFilter; entries outside [from, to] copied
// unchanged; the rawlog format (pairs or observations) kept. Every output is written through
// io::PartialPath / io::AtomicFile: complete or absent.
//
// With threads > 1 the work is pipelined (docs/architecture.md, "Pipelined rawlog filter"): one
// thread reads and decompresses, one detection lane per sensor label (up to `threads` lanes, each
// label's frames in order), the calling thread serializes in entry order, `threads` workers
// compress (RawlogWriter). The output is the same, observation for observation and byte for byte
// once decompressed, as with threads = 1; memory is bounded by the queues.
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>

#include "dynobj/mrptio/DynamicObjectFilter.h"

namespace dynobj::mrptio {

struct RawlogFilterOptions {
  DynamicObjectFilter::Options filter;
  std::size_t from = 0;  ///< first entry to filter (earlier ones are copied)
  std::size_t to = std::numeric_limits<std::size_t>::max();  ///< last entry to filter
  std::string labels_out;     ///< also the detections as a label file v1 ("" = no; one sensor only)
  std::string tracks_out;     ///< also the tracked objects as CSV ("" = no)
  bool overwrite = false;     ///< replace an existing output (never the input itself)
  int compression_level = 1;  ///< output: 0 = plain rawlog, 1 (fastest) .. 3 gzip
  unsigned threads = 0;       ///< 1 = read, detect, write one after another; 0 = one per core
  /// A run that filtered no LiDAR frame (none there, another --sensor-label, frames that do not fit
  /// --sensor) is an error naming what it found, and writes nothing; true: a copy, exit 0.
  bool allow_none = false;
  /// Called after each entry with (entries done, the filter's summary so far). With threads > 1
  /// it is called from the calling thread, in entry order.
  std::function<void(std::size_t, const FilterSummary&)> progress;

  /// `threads`, or the number of hardware threads when it is 0.
  unsigned threadCount() const;
};

struct RawlogFilterSummary {
  std::size_t entries = 0;
  FilterSummary filter;
};

/// Throws RawlogError (damaged input), core::ParameterError, std::runtime_error (output exists,
/// is the input, cannot be written; --labels-out with several LiDARs; no LiDAR frame filtered
/// without allow_none).
RawlogFilterSummary filterRawlog(const std::string& input, const std::string& output,
                                 const RawlogFilterOptions& opts);

}  // namespace dynobj::mrptio
