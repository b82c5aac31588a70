// SPDX-License-Identifier: BSD-3-Clause
// Shared by the apps' mains: command-line parsing and uniform error reporting / exit codes:
//   0 = success (or --help / --version), 1 = a runtime error (bad input, unwritable output, ...),
//   2 = a bad command line.
#pragma once

#include <mrpt/3rdparty/tclap/CmdLine.h>

#include <filesystem>
#include <stdexcept>

#include <exception>
#include <functional>
#include <iostream>
#include <optional>
#include <string>

namespace dynobj::apps {

/// TCLAP output that remembers whether parsing failed (MRPT's TCLAP returns false both for
/// --help and for an error).
class RecordingOutput : public TCLAP::StdOutput {
 public:
  bool failed = false;
  void failure(TCLAP::CmdLineInterface& c, TCLAP::ArgException& e) override {
    failed = true;
    TCLAP::StdOutput::failure(c, e);
  }
};

/// Parses; returns an exit code when the app must stop now (0 after --help, 2 after an error).
inline std::optional<int> parseCommandLine(TCLAP::CmdLine& cmd, int argc, char** argv) {
  static RecordingOutput output;
  cmd.setOutput(&output);
  if (cmd.parse(argc, argv)) return std::nullopt;
  return output.failed ? 2 : 0;
}

/// Creates `dir` (and its parents) if missing; throws naming it when that is impossible.
inline void ensureDirectory(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec || !std::filesystem::is_directory(dir))
    throw std::runtime_error("cannot create output directory '" + dir + "'" +
                             (ec ? ": " + ec.message() : std::string()));
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
