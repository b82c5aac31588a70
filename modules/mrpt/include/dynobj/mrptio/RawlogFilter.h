// SPDX-License-Identifier: BSD-3-Clause
// rawlog-dynobj's job as a library call: rawlog in -> rawlog out, entry by entry (memory stays
// flat), every observation through a DynamicObjectFilter; entries outside [from, to] copied
// unchanged; the rawlog format (pairs or observations) kept. Every output is written through
// io::PartialPath / io::AtomicFile: complete or absent.
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
  std::string labels_out;  ///< also the detections as a label file v1 ("" = no; one sensor only)
  std::string tracks_out;  ///< also the tracked objects as CSV ("" = no)
  bool overwrite = false;  ///< replace an existing output (never the input itself)
  /// Called after each entry with (entries done, the filter's summary so far).
  std::function<void(std::size_t, const FilterSummary&)> progress;
};

struct RawlogFilterSummary {
  std::size_t entries = 0;
  FilterSummary filter;
};

/// Throws RawlogError (damaged input), core::ParameterError, std::runtime_error (output exists,
/// is the input, cannot be written; --labels-out with several LiDARs).
RawlogFilterSummary filterRawlog(const std::string& input, const std::string& output,
                                 const RawlogFilterOptions& opts);

}  // namespace dynobj::mrptio
