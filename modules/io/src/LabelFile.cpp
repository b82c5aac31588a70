// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/LabelFile.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

namespace dynobj::io {
namespace {

constexpr int kMaxSide =
    65535;  ///< rows and cols of a label image (a 128 x 4096 LiDAR is far below)

[[noreturn]] void bad(const std::string& path, std::size_t line, const std::string& what) {
  throw LabelFileError(path + ":" + std::to_string(line) + ": " + what);
}

}  // namespace

LabelFile LabelFile::read(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw LabelFileError(path + ": cannot open label file");
  LabelFile f;
  std::string text;
  std::size_t line_no = 1;
  if (!std::getline(in, text)) bad(path, 1, "empty file (expected '# dynobj-labels v1 ...')");
  {
    char tail = 0;
    f.instances = text.rfind("# dynobj-instances ", 0) == 0;
    const int got = f.instances
                        ? std::sscanf(text.c_str(), "# dynobj-instances v1 rows=%7d cols=%7d %c",
                                      &f.rows, &f.cols, &tail)
                        : std::sscanf(text.c_str(), "# dynobj-labels v1 rows=%7d cols=%7d %c",
                                      &f.rows, &f.cols, &tail);
    if (got != 2 || f.rows <= 0 || f.cols <= 0 || f.rows > kMaxSide || f.cols > kMaxSide)
      bad(path, 1,
          "bad header '" + text + "' (expected '# dynobj-labels v1 rows=<H> cols=<W>'" +
              " or '# dynobj-instances v1 rows=<H> cols=<W>', each at most " +
              std::to_string(kMaxSide) + ")");
  }
  std::string review_line;
  std::size_t review_line_no = 0;
  const std::uint64_t n_pixels =
      static_cast<std::uint64_t>(f.rows) * static_cast<std::uint64_t>(f.cols);
  while (std::getline(in, text)) {
    line_no++;
    if (text.empty()) bad(path, line_no, "empty line");
    if (text.rfind("# reviewed ", 0) == 0 && f.sweeps.empty() && review_line_no == 0) {
      review_line = text.substr(11);
      review_line_no = line_no;
      continue;
    }
    std::istringstream ss(text);
    LabelSweep s;
    long long count = -1;
    if (!(ss >> s.timestamp_ns >> count) || count < 0)
      bad(path, line_no, "expected '<timestamp_ns> <count> <idx>...'");
    if (!f.sweeps.empty() && s.timestamp_ns <= f.sweeps.back().timestamp_ns)
      bad(path, line_no,
          "timestamp " + std::to_string(s.timestamp_ns) + " is not after the previous sweep's");
    if (static_cast<std::uint64_t>(count) > n_pixels)  // before reserving memory for them
      bad(path, line_no,
          "count " + std::to_string(count) + " is more than the " + std::to_string(f.rows) + "x" +
              std::to_string(f.cols) + " image's pixels");
    // Bounded: a count that the indices do not back up must not reserve memory.
    s.pixels.reserve(static_cast<std::size_t>(std::min<long long>(count, 1 << 16)));
    long long idx = 0;
    char colon = 0;
    std::int32_t id = 0;
    while (ss >> idx) {
      if (f.instances && !(ss >> colon >> id && colon == ':'))
        bad(path, line_no, "expected '<idx>:<id>' at pixel " + std::to_string(idx));
      if (idx < 0 || static_cast<std::uint64_t>(idx) >= n_pixels)
        bad(path, line_no,
            "index " + std::to_string(idx) + " is outside the " + std::to_string(f.rows) + "x" +
                std::to_string(f.cols) + " image");
      if (!s.pixels.empty() && static_cast<std::uint32_t>(idx) <= s.pixels.back())
        bad(path, line_no, "indices are not strictly ascending at " + std::to_string(idx));
      s.pixels.push_back(static_cast<std::uint32_t>(idx));
      if (f.instances) s.ids.push_back(id);
    }
    if (!ss.eof()) bad(path, line_no, "non-numeric token");
    if (static_cast<long long>(s.pixels.size()) != count)
      bad(path, line_no,
          "count says " + std::to_string(count) + " but " + std::to_string(s.pixels.size()) +
              " indices follow");
    f.sweeps.push_back(std::move(s));
  }
  if (review_line_no > 0) {
    try {
      f.reviewed = parseSweepRanges(review_line, f.sweeps.size());
    } catch (const std::invalid_argument& e) {
      bad(path, review_line_no, std::string("bad '# reviewed' line: ") + e.what());
    }
    f.has_review = true;
  }
  return f;
}

std::vector<std::size_t> LabelFile::unreviewedSweeps() const {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < sweeps.size(); k++)
    if (!isReviewed(k)) out.push_back(k);
  return out;
}

void LabelFile::requireReviewed(const std::string& path) const {
  const auto missing = unreviewedSweeps();
  if (missing.empty()) return;
  std::vector<std::uint8_t> flags(sweeps.size(), 0);
  for (std::size_t k : missing) flags[k] = 1;
  std::string list = formatSweepRanges(flags);
  if (list.size() > 60) list = list.substr(0, 57) + "...";
  throw LabelFileError(path + ": " + std::to_string(missing.size()) + " of " +
                       std::to_string(sweeps.size()) +
                       " sweeps were not reviewed by a person (sweeps " + list +
                       "): review them in dynobj-label, or score only the reviewed ones"
                       " (dynobj-eval --unreviewed skip)");
}

void LabelFile::keepReviewedOnly() {
  if (!has_review) return;
  std::vector<LabelSweep> kept;
  for (std::size_t k = 0; k < sweeps.size(); k++)
    if (isReviewed(k)) kept.push_back(std::move(sweeps[k]));
  sweeps = std::move(kept);
  reviewed.assign(sweeps.size(), 1);
}

std::string formatSweepRanges(const std::vector<std::uint8_t>& flags) {
  std::string out;
  for (std::size_t k = 0; k < flags.size();) {
    if (!flags[k]) {
      k++;
      continue;
    }
    std::size_t end = k;
    while (end + 1 < flags.size() && flags[end + 1]) end++;
    if (!out.empty()) out += ',';
    out += std::to_string(k);
    if (end > k) out += "-" + std::to_string(end);
    k = end + 1;
  }
  return out.empty() ? "none" : out;
}

std::vector<std::uint8_t> parseSweepRanges(const std::string& text, std::size_t n) {
  std::vector<std::uint8_t> flags(n, 0);
  if (text == "none") return flags;
  if (text.empty()) throw std::invalid_argument("empty list (write 'none' for no sweep)");
  std::size_t pos = 0;
  const auto number = [&](std::size_t& v) {
    const std::size_t start = pos;
    v = 0;
    while (pos < text.size() && text[pos] >= '0' && text[pos] <= '9') {
      v = v * 10 + static_cast<std::size_t>(text[pos] - '0');
      if (v > n) throw std::invalid_argument("sweep " + text.substr(start) + " does not exist");
      pos++;
    }
    if (pos == start)
      throw std::invalid_argument("expected a sweep number at '" + text.substr(start) + "'");
  };
  while (pos < text.size()) {
    std::size_t a = 0, b = 0;
    number(a);
    b = a;
    if (pos < text.size() && text[pos] == '-') {
      pos++;
      number(b);
    }
    if (b < a || b >= n)
      throw std::invalid_argument("sweeps " + std::to_string(a) + "-" + std::to_string(b) +
                                  " are not within the file's " + std::to_string(n) + " sweeps");
    for (std::size_t k = a; k <= b; k++) flags[k] = 1;
    if (pos < text.size() && text[pos++] != ',')
      throw std::invalid_argument("expected ',' between ranges");
    if (pos == text.size() && text.back() == ',')
      throw std::invalid_argument("the list ends with ','");
  }
  return flags;
}

std::vector<std::uint32_t> pixelsOfMask(const cv::Mat_<std::uint8_t>& mask) {
  std::vector<std::uint32_t> out;
  for (int r = 0; r < mask.rows; r++) {
    const std::uint8_t* row = mask.ptr<std::uint8_t>(r);
    for (int c = 0; c < mask.cols; c++)
      if (row[c]) out.push_back(static_cast<std::uint32_t>(r * mask.cols + c));
  }
  return out;
}

cv::Mat_<std::uint8_t> maskOfPixels(const std::vector<std::uint32_t>& pixels, int rows, int cols) {
  cv::Mat_<std::uint8_t> m(rows, cols, std::uint8_t{0});
  for (std::uint32_t px : pixels) m(static_cast<int>(px) / cols, static_cast<int>(px) % cols) = 255;
  return m;
}

LabelFileWriter::LabelFileWriter(const std::string& path, int rows, int cols, bool instances)
    : file_(path), rows_(rows), cols_(cols), instances_(instances) {
  if (rows <= 0 || cols <= 0) throw std::invalid_argument("LabelFileWriter: bad image size");
  file_.stream() << (instances ? "# dynobj-instances v1 rows=" : "# dynobj-labels v1 rows=") << rows
                 << " cols=" << cols << "\n";
}

void LabelFileWriter::writeReviewed(const std::vector<std::uint8_t>& reviewed) {
  if (any_) throw std::logic_error("LabelFileWriter: the '# reviewed' line goes before the sweeps");
  if (review_count_ >= 0) throw std::logic_error("LabelFileWriter: one '# reviewed' line only");
  file_.stream() << "# reviewed " << formatSweepRanges(reviewed) << "\n";
  review_count_ = static_cast<std::int64_t>(reviewed.size());
}

void LabelFileWriter::write(std::int64_t timestamp_ns, const std::vector<std::uint32_t>& pixels,
                            const std::vector<std::int32_t>& ids) {
  if (any_ && timestamp_ns <= last_ts_)
    throw std::invalid_argument("LabelFileWriter: timestamps must increase");
  if (ids.size() != (instances_ ? pixels.size() : 0))
    throw std::invalid_argument(
        "LabelFileWriter: an instance file needs one id per pixel, a label file none");
  const auto n = static_cast<std::uint64_t>(rows_) * static_cast<std::uint64_t>(cols_);
  file_.stream() << timestamp_ns << ' ' << pixels.size();
  for (std::size_t i = 0; i < pixels.size(); i++) {
    if (pixels[i] >= n || (i > 0 && pixels[i] <= pixels[i - 1]))
      throw std::invalid_argument("LabelFileWriter: pixels must be ascending and inside the image");
    file_.stream() << ' ' << pixels[i];
    if (instances_) file_.stream() << ':' << ids[i];
  }
  file_.stream() << '\n';
  any_ = true;
  last_ts_ = timestamp_ns;
  written_++;
}

void LabelFileWriter::close() {
  if (review_count_ >= 0 && static_cast<std::size_t>(review_count_) != written_)
    throw std::logic_error("LabelFileWriter: the '# reviewed' line covers " +
                           std::to_string(review_count_) + " sweeps but " +
                           std::to_string(written_) + " were written");
  file_.commit();
}

}  // namespace dynobj::io
