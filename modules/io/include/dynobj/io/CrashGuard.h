// SPDX-License-Identifier: BSD-3-Clause
// The last line of defence for "no output that looks complete but is not": if a tool dies of a
// signal (a crash inside a library, an abort, Ctrl-C, kill), the `.partial` files it was writing
// are removed by an async-signal-safe handler, which also says which input entry was being read.
// AtomicFile and PartialPath register their partial paths here themselves; apps call
// installCrashGuard() once (apps/common/AppMain.h runApp() does).
//
// Fatal signals (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT): partial files removed, a message
// "<app>: fatal error: <signal> at entry N (byte B) of '<input>'" (the last entry the reader
// started), exit code 3 (after the previously installed handler, e.g. a sanitizer's, has run).
// SIGINT, SIGTERM, SIGHUP: partial files removed, then the process dies of the signal as usual.
#pragma once

#include <cstdint>
#include <string>

namespace dynobj::io {

/// Exit code of a process stopped by the crash guard after a fatal signal.
constexpr int kCrashExitCode = 3;

/// Installs the signal handlers (idempotent). `app` is used in the message (copied).
void installCrashGuard(const std::string& app);

/// Registers a path (file or folder) to remove if the process dies; returns a handle for
/// unregisterPartialOutput(), or -1 if the table (64 entries) is full. Thread-safe.
int registerPartialOutput(const std::string& path);
void unregisterPartialOutput(int handle);

/// What is being read, for the crash message: the input file (copied; call when opening it)...
void setCrashInput(const std::string& path);
/// ... and the entry being read and its byte offset (cheap: two atomic stores).
void setCrashPosition(std::uint64_t entry, std::uint64_t byte);

}  // namespace dynobj::io
