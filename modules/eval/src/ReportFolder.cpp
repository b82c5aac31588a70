// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/ReportFolder.h"

#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/io/Png.h>

#include <cstdio>
#include <filesystem>
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

RunResult scoreLabelFiles(const std::string& gt, const std::string& pred) {
  RunResult r;
  r.mode = "files";
  r.description = std::filesystem::path(pred).filename().string();
  r.sequence = std::filesystem::path(gt).filename().string();
  r.sequence = r.sequence.substr(0, r.sequence.find('.'));  // hall.gt.labels -> hall
  const io::LabelFile truth = io::LabelFile::read(gt);
  r.metrics = SequenceMetrics::compute(truth, io::LabelFile::read(pred));
  r.rows = truth.rows;
  r.cols = truth.cols;
  return r;
}

}  // namespace dynobj::eval
