// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/ReportFolder.h"

#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/io/Png.h>

#include <cstdio>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "dynobj/eval/Overlay.h"
#include "dynobj/eval/Report.h"

namespace dynobj::eval {

std::string writeReportFolder(const std::string& dir, const std::string& title,
                              const std::string& command, const std::vector<RunResult>& runs) {
  std::error_code ec;
  std::filesystem::create_directories(dir + "/overlays", ec);
  if (!std::filesystem::is_directory(dir + "/overlays"))
    throw std::runtime_error("cannot create output directory '" + dir + "'");
  const std::string table = markdownTable(runs);
  io::writeFileAtomically(dir + "/summary.md", table);
  writeJsonSummary(dir + "/summary.json", runs);
  std::vector<std::pair<std::string, cv::Mat>> sheet;
  for (const auto& r : runs) {
    writeSweepCsv(dir + "/" + r.sequence + "." + r.mode + ".sweeps.csv", r);
    for (const auto& [sweep, img] : r.overlays) {
      char name[32];
      std::snprintf(name, sizeof(name), ".sweep-%04d.png", sweep);
      io::writePng(dir + "/overlays/" + r.sequence + "." + r.mode + name, img);
      sheet.emplace_back(r.sequence + " " + r.mode + ", sweep " + std::to_string(sweep), img);
    }
  }
  if (!sheet.empty()) io::writePng(dir + "/overlays/contact-sheet.png", contactSheet(sheet));
  writeHtmlReport(dir + "/report.html", title, command, runs);
  return table;
}

RunResult scoreLabelFiles(const std::string& gt, const std::string& pred,
                          const std::string& unreviewed) {
  if (unreviewed != "refuse" && unreviewed != "skip" && unreviewed != "include")
    throw std::invalid_argument("--unreviewed must be refuse, skip or include (got '" + unreviewed +
                                "')");
  RunResult r;
  r.mode = "files";
  r.description = std::filesystem::path(pred).filename().string();
  r.sequence = std::filesystem::path(gt).filename().string();
  r.sequence = r.sequence.substr(0, r.sequence.find('.'));  // hall.gt.labels -> hall
  io::LabelFile truth = io::LabelFile::read(gt);
  io::LabelFile predicted = io::LabelFile::read(pred);
  if (unreviewed == "refuse") truth.requireReviewed(gt);
  if (unreviewed == "skip" && truth.has_review) {
    truth.keepReviewedOnly();
    if (truth.sweeps.empty()) throw std::runtime_error(gt + ": no sweep was reviewed");
    std::set<std::int64_t> keep;
    for (const auto& s : truth.sweeps) keep.insert(s.timestamp_ns);
    std::vector<io::LabelSweep> kept;
    for (auto& s : predicted.sweeps)
      if (keep.count(s.timestamp_ns)) kept.push_back(std::move(s));
    predicted.sweeps = std::move(kept);
  }
  r.metrics = SequenceMetrics::compute(truth, predicted);
  r.rows = truth.rows;
  r.cols = truth.cols;
  return r;
}

}  // namespace dynobj::eval
