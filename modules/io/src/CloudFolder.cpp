// SPDX-License-Identifier: BSD-3-Clause
// CloudFolder: lists a folder of sweep files in natural name order and reads their time stamps.
#include "dynobj/io/CloudFolder.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "dynobj/io/KittiBin.h"
#include "dynobj/io/PcdFile.h"
#include "dynobj/io/PoseFile.h"

namespace dynobj::io {

bool naturalLess(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      std::size_t ei = i, ej = j;
      while (ei < a.size() && digit(a[ei])) ei++;
      while (ej < b.size() && digit(b[ej])) ej++;
      std::string x = a.substr(i, ei - i), y = b.substr(j, ej - j);
      x.erase(0, std::min(x.find_first_not_of('0'), x.size()));
      y.erase(0, std::min(y.find_first_not_of('0'), y.size()));
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      i = ei;
      j = ej;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      i++;
      j++;
    }
  }
  if (a.size() - i != b.size() - j) return a.size() - i < b.size() - j;
  return a < b;
}

namespace {

namespace fs = std::filesystem;

/// "YYYY-MM-DD HH:MM:SS[.fraction]" (UTC) in ns since 1970, or -1 when `s` is not one.
std::int64_t parseDateTimeNs(const std::string& s) {
  int y = 0, mo = 0, d = 0, h = 0, mi = 0, n = 0;
  if (std::sscanf(s.c_str(), "%4d-%2d-%2d %2d:%2d:%n", &y, &mo, &d, &h, &mi, &n) != 5 || n == 0 ||
      y < 1970 || mo < 1 || mo > 12 || d < 1 || d > 31 || h > 23 || mi > 59)
    return -1;
  const auto sec = parseSecondsNs(s.substr(static_cast<std::size_t>(n)));
  if (!sec || *sec < 0 || *sec >= 61000000000LL) return -1;
  const auto leap = [](int yr) { return (yr % 4 == 0 && yr % 100 != 0) || yr % 400 == 0; };
  static const int kDaysBefore[12] = {0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334};
  std::int64_t days = kDaysBefore[mo - 1] + (mo > 2 && leap(y)) + d - 1;
  for (int yr = 1970; yr < y; yr++) days += leap(yr) ? 366 : 365;
  return ((days * 24 + h) * 60 + mi) * 60000000000LL + *sec;
}

std::vector<std::int64_t> readTimes(const std::string& path) {
  std::ifstream in(path);
  if (!in) throwFormatError(path, "cannot open times file");
  std::vector<std::int64_t> out;
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    line_no++;
    line = line.substr(0, line.find('#'));
    const auto b = line.find_first_not_of(" \t\r"), e = line.find_last_not_of(" \t\r");
    if (b == std::string::npos) continue;
    const std::string s = line.substr(b, e - b + 1);
    std::int64_t t = parseDateTimeNs(s);
    if (t < 0 && s.find_first_of(".eE") == std::string::npos) {  // an integer: nanoseconds
      const char* end = s.data() + s.size();
      if (std::from_chars(s.data(), end, t).ptr != end) t = -1;
    } else if (t < 0) {
      t = parseSecondsNs(s).value_or(-1);
    }
    const std::string where = path + ":" + std::to_string(line_no);
    if (t < 0) throwFormatError(where, "'" + s + "' is not a time stamp");
    if (!out.empty() && t <= out.back())
      throwFormatError(where, "time stamp '" + s + "' is not after the previous one");
    out.push_back(t);
  }
  return out;
}

}  // namespace

CloudFolder::CloudFolder(const std::string& dir, const std::string& times_file) : dir_(dir) {
  if (!fs::is_directory(dir)) throwFormatError(dir, "not a folder");
  std::vector<std::string> pcd, bin;
  for (const auto& e : fs::directory_iterator(dir)) {
    std::string ext = e.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (!e.is_regular_file() || e.path().filename().string()[0] == '.') continue;
    if (ext == ".pcd") pcd.push_back(e.path().string());
    if (ext == ".bin") bin.push_back(e.path().string());
  }
  if (pcd.empty() && bin.empty()) throwFormatError(dir, "holds no .pcd or .bin file");
  if (!pcd.empty() && !bin.empty())
    throwFormatError(dir, "holds both .pcd (" + std::to_string(pcd.size()) + ") and .bin (" +
                              std::to_string(bin.size()) + ") files: keep one format per folder");
  ext_ = pcd.empty() ? ".bin" : ".pcd";
  files_ = pcd.empty() ? std::move(bin) : std::move(pcd);
  std::sort(files_.begin(), files_.end(), naturalLess);
  if (times_file.empty()) return;
  times_ns_ = readTimes(times_file);
  if (times_ns_.size() != files_.size())
    throwFormatError(times_file, std::to_string(times_ns_.size()) + " time stamps for " +
                                     std::to_string(files_.size()) + " sweeps in " + dir);
}

std::int64_t CloudFolder::timestampNs(std::size_t k) const {
  if (k >= files_.size()) throw std::out_of_range("CloudFolder: no sweep " + std::to_string(k));
  return hasTimes() ? times_ns_[k] : static_cast<std::int64_t>(k) * period_ns_;
}

void CloudFolder::setPeriodNs(std::int64_t period_ns) {
  if (period_ns <= 0) throw std::invalid_argument("CloudFolder: the sweep period must be > 0");
  period_ns_ = period_ns;
}

CloudFile CloudFolder::read(std::size_t k) const {
  return ext_ == ".pcd" ? readPcd(path(k)) : readKittiBin(path(k));
}

}  // namespace dynobj::io
