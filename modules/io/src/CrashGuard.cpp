// SPDX-License-Identifier: BSD-3-Clause
// Everything the handler touches is static storage and lock-free atomics; it calls only
// async-signal-safe functions (write, unlink, rmdir, fork, execve, waitpid, sigaction, raise,
// _exit).
#include "dynobj/io/CrashGuard.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <mutex>

namespace dynobj::io {
namespace {

constexpr int kSlots = 64;
constexpr std::size_t kPathMax = 4096;

enum SlotState : int { kFree = 0, kFilling = 1, kReady = 2 };

struct Slot {
  std::atomic<int> state{kFree};
  char path[kPathMax];
};

Slot g_slots[kSlots];
std::mutex g_register_mutex;  // registration only; never taken in the handler

char g_app[128] = "dynobj";
char g_input[kPathMax];
std::atomic<bool> g_input_set{false};
std::atomic<std::uint64_t> g_entry{0}, g_byte{0};
std::atomic<bool> g_position_set{false};
std::atomic<bool> g_in_handler{false};

constexpr int kFatal[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
constexpr int kStop[] = {SIGINT, SIGTERM, SIGHUP};
struct sigaction g_previous[65];
bool g_installed = false;
alignas(16) char g_alt_stack[1 << 16];

// --- async-signal-safe output
void put(const char* s) {
  std::size_t n = 0;
  while (s[n]) n++;
  while (n > 0) {
    const ssize_t w = ::write(STDERR_FILENO, s, n);
    if (w <= 0) return;
    s += w;
    n -= static_cast<std::size_t>(w);
  }
}
void putNumber(std::uint64_t v) {
  char buf[24];
  int i = 23;
  buf[i] = 0;
  do {
    buf[--i] = static_cast<char>('0' + v % 10);
    v /= 10;
  } while (v > 0 && i > 0);
  put(buf + i);
}
const char* signalName(int sig) {
  switch (sig) {
    case SIGSEGV:
      return "SIGSEGV (invalid memory access)";
    case SIGBUS:
      return "SIGBUS (bus error)";
    case SIGFPE:
      return "SIGFPE (arithmetic error)";
    case SIGILL:
      return "SIGILL (illegal instruction)";
    case SIGABRT:
      return "SIGABRT (abort)";
    case SIGINT:
      return "SIGINT";
    case SIGTERM:
      return "SIGTERM";
    case SIGHUP:
      return "SIGHUP";
    default:
      return "a signal";
  }
}

/// Removes a file, or a folder with its content (rm -rf in a child process: the handler cannot
/// walk a tree safely).
void removePath(const char* path) {
  if (::unlink(path) == 0 || errno == ENOENT) return;
  if (::rmdir(path) == 0) return;
  const pid_t pid = ::fork();
  if (pid == 0) {
    char rm[] = "/bin/rm", rf[] = "-rf", dd[] = "--";
    char* argv[] = {rm, rf, dd, const_cast<char*>(path), nullptr};
    char* envp[] = {nullptr};
    ::execve(rm, argv, envp);
    ::_exit(127);
  }
  if (pid > 0) {
    int status = 0;
    ::waitpid(pid, &status, 0);
  }
}

/// Removes every registered partial output; returns how many were registered.
int removePartials(bool report) {
  int n = 0;
  for (auto& s : g_slots) {
    if (s.state.load(std::memory_order_acquire) != kReady) continue;
    removePath(s.path);
    if (report) {
      put(g_app);
      put(": removed the unfinished output '");
      put(s.path);
      put("'\n");
    }
    n++;
  }
  return n;
}

void onSignal(int sig, siginfo_t* info, void* ctx) {
  const int saved_errno = errno;
  const bool fatal = sig != SIGINT && sig != SIGTERM && sig != SIGHUP;
  if (g_in_handler.exchange(true)) {  // a second signal while cleaning up: just die
    ::signal(sig, SIG_DFL);
    ::raise(sig);
    ::_exit(fatal ? kCrashExitCode : 128 + sig);
  }
  put("\n");
  put(g_app);
  put(fatal ? ": fatal error: " : ": interrupted: ");
  put(signalName(sig));
  if (g_input_set.load(std::memory_order_acquire)) {
    if (g_position_set.load(std::memory_order_acquire)) {
      put(" at entry ");
      putNumber(g_entry.load(std::memory_order_relaxed));
      put(" (byte ");
      putNumber(g_byte.load(std::memory_order_relaxed));
      put(") of '");
    } else {
      put(" while reading '");
    }
    put(g_input);
    put("'");
  }
  put("\n");
  removePartials(true);
  if (fatal) {
    put(g_app);
    put(": this is a bug (damaged input must end in an error message, not a crash); please "
        "report it with the input file\n");
    // A sanitizer's or debugger's handler installed before ours gets its turn (its report).
    const struct sigaction& prev = g_previous[sig];
    if ((prev.sa_flags & SA_SIGINFO) && prev.sa_sigaction) {
      prev.sa_sigaction(sig, info, ctx);
    } else if (!(prev.sa_flags & SA_SIGINFO) && prev.sa_handler != SIG_DFL &&
               prev.sa_handler != SIG_IGN) {
      prev.sa_handler(sig);
    }
    ::_exit(kCrashExitCode);
  }
  errno = saved_errno;
  ::signal(sig, SIG_DFL);  // die of the signal, as the caller expects
  ::raise(sig);
}

void copyString(char* dst, std::size_t cap, const std::string& s) {
  const std::size_t n = std::min(s.size(), cap - 1);
  std::memcpy(dst, s.data(), n);
  dst[n] = 0;
}

}  // namespace

void installCrashGuard(const std::string& app) {
  std::lock_guard<std::mutex> lock(g_register_mutex);
  copyString(g_app, sizeof g_app, app);
  if (g_installed) return;
  g_installed = true;
  stack_t ss{};  // so that a stack overflow can still be reported
  ss.ss_sp = g_alt_stack;
  ss.ss_size = sizeof g_alt_stack;
  ::sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_sigaction = onSignal;
  sa.sa_flags = SA_SIGINFO | SA_ONSTACK;
  sigemptyset(&sa.sa_mask);
  for (int sig : kFatal) ::sigaction(sig, &sa, &g_previous[sig]);
  for (int sig : kStop) {
    struct sigaction old {};
    ::sigaction(sig, nullptr, &old);
    if (old.sa_handler == SIG_IGN) continue;  // e.g. nohup: keep ignoring
    ::sigaction(sig, &sa, &g_previous[sig]);
  }
}

int registerPartialOutput(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_register_mutex);
  for (int i = 0; i < kSlots; i++) {
    int expected = kFree;
    if (!g_slots[i].state.compare_exchange_strong(expected, kFilling)) continue;
    copyString(g_slots[i].path, kPathMax, path);
    g_slots[i].state.store(kReady, std::memory_order_release);
    return i;
  }
  return -1;
}

void unregisterPartialOutput(int handle) {
  if (handle < 0 || handle >= kSlots) return;
  g_slots[handle].state.store(kFree, std::memory_order_release);
}

void setCrashInput(const std::string& path) {
  std::lock_guard<std::mutex> lock(g_register_mutex);
  g_input_set.store(false, std::memory_order_release);
  g_position_set.store(false, std::memory_order_release);
  copyString(g_input, kPathMax, path);
  g_input_set.store(true, std::memory_order_release);
}

void setCrashPosition(std::uint64_t entry, std::uint64_t byte) {
  g_entry.store(entry, std::memory_order_relaxed);
  g_byte.store(byte, std::memory_order_relaxed);
  g_position_set.store(true, std::memory_order_release);
}

}  // namespace dynobj::io
