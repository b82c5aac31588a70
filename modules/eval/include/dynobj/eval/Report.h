// SPDX-License-Identifier: BSD-3-Clause
// Reports of evaluation runs: a Markdown table laid out like the paper's Table I (precision, IoU,
// recall, F1, plus object recall, static points flagged and ms/frame), a per-sweep CSV, a JSON
// summary and one self-contained HTML page (tables, per-sweep plots as inline SVG, overlay images
// as inline PNG). Every file is written through io::AtomicFile (complete or absent).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "dynobj/eval/RunResult.h"

namespace dynobj::eval {

/// The summary table (Markdown), one row per run.
std::string markdownTable(const std::vector<RunResult>& runs);

/// sweep,timestamp_ns,tp,fp,fn,tn,precision,recall,iou,f1,ms (undefined metrics left empty).
void writeSweepCsv(const std::string& path, const RunResult& run);

/// Every run's micro metrics, distributions, object recall and timings.
void writeJsonSummary(const std::string& path, const std::vector<RunResult>& runs);

/// The HTML report; `command` is printed on it (how to regenerate).
void writeHtmlReport(const std::string& path, const std::string& title, const std::string& command,
                     const std::vector<RunResult>& runs);

}  // namespace dynobj::eval
