// SPDX-License-Identifier: BSD-3-Clause
// Shared by the apps' mains: command-line parsing and uniform error reporting / exit codes:
//   0 = success (or --help / --version), 1 = a runtime error (bad input, unwritable output, ...),
//   2 = a bad command line.
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>

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

/// Creates `dir` (and its parents) if missing; throws naming it when that is impossible.
inline void ensureDirectory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw std::runtime_error("cannot create output directory '" + dir + "'" +
                             (ec ? ": " + ec.message() : std::string()));
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

/// Runs `body`, printing "<app>: error: <message>" and returning 1 on an exception.
inline int runApp(const std::string& app, const std::function<int()>& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << app << ": error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace dynobj::apps
