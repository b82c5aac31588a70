// SPDX-License-Identifier: BSD-3-Clause
// Shared by the apps' mains: command-line parsing and uniform error reporting / exit codes:
//   0 = success (or --help / --version), 1 = a runtime error (bad input, unwritable output, ...),
//   2 = a bad command line, 3 = crashed (a fatal signal caught by the crash guard, which removed
//   the unfinished outputs: io/CrashGuard.h).
#pragma once

#include <dynobj/io/CrashGuard.h>
#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <initializer_list>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace dynobj::apps {

/// Parses; returns an exit code when the app must stop now: 0 after --help / --version, 2 after
/// a command-line error (MRPT's TCLAP prints the message and returns false in both cases).
inline std::optional<int> parseCommandLine(TCLAP::CmdLine& cmd, int argc, char** argv) {
  if (cmd.parse(argc, argv)) return std::nullopt;
  for (int i = 1; i < argc; i++) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help" || a == "--version") return 0;
  }
  return 2;
}

/// -o/--output, the app's output (a file, or a folder for many files), as in every dynobj app and
/// MRPT's own; `old_name` (e.g. "out-dir") is the app's earlier long spelling, still accepted.
class OutputArg {
 public:
  OutputArg(TCLAP::CmdLine& cmd, const std::string& desc, bool required, const std::string& type,
            const std::string& old_name, const std::string& fallback = "")
      : out_("o", "output", desc, required, fallback, type),
        old_("", old_name, "Same as --output (earlier spelling)", required, fallback, type) {
    if (old_name.empty())
      cmd.add(out_);
    else if (required)
      cmd.xorAdd(out_, old_);
    else
      cmd.add(out_), cmd.add(old_);
  }
  bool isSet() const { return out_.isSet() || old_.isSet(); }
  const std::string& getValue() const { return old_.isSet() ? old_.getValue() : out_.getValue(); }

 private:
  mutable TCLAP::ValueArg<std::string> out_, old_;  // TCLAP's getters are not const
};

/// Creates `dir` (and its parents) if missing; throws naming it when that is impossible.
inline void ensureDirectory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw std::runtime_error("cannot create output directory '" + dir + "'" +
                             (ec ? ": " + ec.message() : std::string()));
}

/// An output folder made for this run (ensureDirectory): destroyed before keep() (the run
/// failed), the folders it created are removed again while they are empty, so that an error leaves
/// no empty folder behind.
class OutputFolder {
 public:
  explicit OutputFolder(const std::string& dir) {
    namespace fs = std::filesystem;
    for (fs::path p = fs::path(dir).lexically_normal(); !p.empty() && !fs::exists(p);
         p = p.parent_path()) {
      created_.push_back(p);  // deepest first
      if (p == p.parent_path()) break;
    }
    ensureDirectory(dir);
  }
  ~OutputFolder() {
    if (kept_) return;
    std::error_code ec;
    for (const auto& p : created_)
      if (!std::filesystem::is_empty(p, ec) || ec || !std::filesystem::remove(p, ec)) break;
  }
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;
  /// The run succeeded: the folder stays, even empty.
  void keep() { kept_ = true; }

 private:
  std::vector<std::filesystem::path> created_;
  bool kept_ = false;
};

/// Throws "output '<path>' exists (use -w to replace it)" for the first non-empty path of `paths`
/// that exists, unless `overwrite`: no tool replaces an output without -w.
inline void refuseExisting(std::initializer_list<std::string> paths, bool overwrite) {
  if (overwrite) return;
  for (const auto& p : paths)
    if (!p.empty() && std::filesystem::exists(p))
      throw std::runtime_error("output '" + p + "' exists (use -w to replace it)");
}

/// Whether every non-empty path of `paths` exists (for --skip-existing: our outputs are written
/// as <file>.partial and renamed when complete, so an existing output is a complete one).
inline bool allExist(std::initializer_list<std::string> paths) {
  for (const auto& p : paths)
    if (!p.empty() && !std::filesystem::exists(p)) return false;
  return true;
}

/// The shipped data folder (share/dynobj): $DYNOBJ_SHARE if set, else the source tree's when
/// run from a build tree, else the installed one.
inline std::string shareDir() {
  if (const char* env = std::getenv("DYNOBJ_SHARE")) return env;
#ifdef DYNOBJ_SHARE_DIR_BUILD
  if (std::filesystem::is_directory(DYNOBJ_SHARE_DIR_BUILD)) return DYNOBJ_SHARE_DIR_BUILD;
#endif
#ifdef DYNOBJ_SHARE_DIR_INSTALLED
  return DYNOBJ_SHARE_DIR_INSTALLED;
#else
  return "share/dynobj";
#endif
}

/// The time left of a long stage, from the share of its work done: the rate since the first
/// share given (so a stage that starts late, e.g. after a skipped part of the input, is not
/// misjudged). update() returns "" until the estimate means something (5 s and 1 % in), then
/// e.g. "~4 min left".
class TimeLeft {
 public:
  std::string update(double fraction) {
    const auto now = std::chrono::steady_clock::now();
    if (fraction < 0) return "";
    if (first_ < 0) {
      first_ = fraction;
      start_ = now;
      return "";
    }
    const double s = std::chrono::duration<double>(now - start_).count();
    if (s < 5 || fraction - first_ < 0.01 || fraction >= 1) return "";
    const double left = s * (1.0 - fraction) / (fraction - first_);
    char b[48];
    if (left < 90)
      std::snprintf(b, sizeof(b), "~%.0f s left", left);
    else if (left < 5400)
      std::snprintf(b, sizeof(b), "~%.0f min left", left / 60);
    else
      std::snprintf(b, sizeof(b), "~%.1f h left", left / 3600);
    return b;
  }

 private:
  double first_ = -1;
  std::chrono::steady_clock::time_point start_;
};

/// Runs `body`, printing "<app>: error: <message>" and returning 1 on an exception. The crash
/// guard is installed first: a crash or a kill removes the `.partial` outputs.
inline int runApp(const std::string& app, const std::function<int()>& body) {
  dynobj::io::installCrashGuard(app);
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << app << ": error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace dynobj::apps
