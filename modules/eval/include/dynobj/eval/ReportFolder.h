// SPDX-License-Identifier: BSD-3-Clause
// dynobj-eval's output folder (docs/formats.md §7): summary.md (returned too, for stdout),
// summary.json, <sequence>.<mode>.sweeps.csv, overlays/*.png + overlays/contact-sheet.png and
// report.html; and the scoring of two existing label files (no frames: no overlays or timings).
#pragma once

#include <string>
#include <vector>

#include "dynobj/eval/RunResult.h"

namespace dynobj::eval {

/// Writes every file into `dir` (created with overlays/ if missing); returns the Markdown table.
std::string writeReportFolder(const std::string& dir, const std::string& title,
                              const std::string& command, const std::vector<RunResult>& runs);

/// Ground truth vs predictions, sweep by sweep (mode "files"; sequence = gt's name up to the
/// first '.'). Ground truth made by people records the sweeps they reviewed (`# reviewed`):
/// `unreviewed` says what to do with the others: "refuse" (throw naming them), "skip" (score the
/// reviewed sweeps only) or "include" (score them as they are).
RunResult scoreLabelFiles(const std::string& gt, const std::string& pred,
                          const std::string& unreviewed = "refuse");

}  // namespace dynobj::eval
