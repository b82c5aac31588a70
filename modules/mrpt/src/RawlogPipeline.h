// SPDX-License-Identifier: BSD-3-Clause
// Internal: filterRawlog's pipelined loop (threads > 1).
#pragma once

#include <functional>

#include "dynobj/mrptio/RawlogFilter.h"
#include "dynobj/mrptio/RawlogReader.h"
#include "dynobj/mrptio/RawlogWriter.h"

namespace dynobj::mrptio::detail {

/// Called for every filtered observation in entry order with its detection (nullptr when it was
/// not processed).
using ResultSink =
    std::function<void(const mrpt::obs::CObservation&, const core::DetectionResult*)>;

/// Reads `reader` to its end in a thread of its own, detects in one lane per sensor label (at most
/// `threads` lanes; each label's frames in order, different labels in parallel), and writes every
/// entry in order to `out` from the calling thread (which compresses with its own workers). Gives
/// the same output, results and summary as the single-threaded loop. `keep_results`: copy each
/// detection for `on_result` (else it gets nullptr-free calls only when needed, see .cpp).
RawlogFilterSummary filterPipelined(RawlogReader& reader, RawlogWriter& out,
                                    const RawlogFilterOptions& o, unsigned threads,
                                    const ResultSink& on_result, bool keep_results);

}  // namespace dynobj::mrptio::detail
