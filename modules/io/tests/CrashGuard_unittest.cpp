// SPDX-License-Identifier: BSD-3-Clause
// The crash guard, in forked children (gtest death tests): a fatal signal or a kill while an
// AtomicFile / PartialPath is open removes its .partial and says what was being read.
#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/CrashGuard.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/system/filesystem.h>
#include <sys/wait.h>

#include <csignal>
#include <filesystem>
#include <fstream>

using namespace dynobj::io;

namespace {

[[noreturn]] void crashWhileWriting(const std::string& file, const std::string& folder, int sig) {
  installCrashGuard("guard-test");
  AtomicFile f(file);
  f.stream() << "half" << std::flush;
  PartialPath dir(folder);
  std::filesystem::create_directories(dir.partial() + "/sub");
  std::ofstream(dir.partial() + "/sub/x.png") << "x";
  setCrashInput("/data/in.rawlog");
  setCrashPosition(12, 4534811);
  std::raise(sig);
  std::_Exit(0);  // not reached: the signal ends the process
}

#if defined(__SANITIZE_ADDRESS__)
constexpr bool kAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kAsan = true;
#else
constexpr bool kAsan = false;
#endif
#else
constexpr bool kAsan = false;
#endif

/// Exit code 3; in an AddressSanitizer build ASan's own SIGSEGV handler, which the guard calls
/// after its clean-up, reports and exits with 1 first.
bool crashExit(int status) {
  return WIFEXITED(status) &&
         (WEXITSTATUS(status) == kCrashExitCode || (kAsan && WEXITSTATUS(status) == 1));
}

}  // namespace

TEST(CrashGuardDeathTest, FatalSignalRemovesPartialsNamesTheEntryAndExitsWithCode3) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  const std::string base = dynobj::testing::scratchPath("");
  const std::string file = base + ".rawlog", folder = base + "-frames";
  EXPECT_EXIT(crashWhileWriting(file, folder, SIGSEGV), crashExit,
              "guard-test: fatal error: SIGSEGV.*at entry 12 \\(byte 4534811\\) of "
              "'/data/in.rawlog'");
  EXPECT_FALSE(std::filesystem::exists(partialName(file)));
  EXPECT_FALSE(std::filesystem::exists(partialName(folder)));
  EXPECT_FALSE(std::filesystem::exists(file));
}

TEST(CrashGuardDeathTest, AbortIsCaughtToo) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  const std::string base = dynobj::testing::scratchPath("");
  EXPECT_EXIT(crashWhileWriting(base + ".txt", base + "-d", SIGABRT),
              ::testing::ExitedWithCode(kCrashExitCode), "SIGABRT");
  EXPECT_FALSE(std::filesystem::exists(partialName(base + ".txt")));
  EXPECT_FALSE(std::filesystem::exists(partialName(base + "-d")));
}

TEST(CrashGuardDeathTest, TerminationRemovesPartialsAndDiesOfTheSignal) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  const std::string base = dynobj::testing::scratchPath("");
  EXPECT_EXIT(crashWhileWriting(base + ".txt", base + "-d", SIGTERM),
              ::testing::KilledBySignal(SIGTERM), "interrupted: SIGTERM");
  EXPECT_FALSE(std::filesystem::exists(partialName(base + ".txt")));
  EXPECT_FALSE(std::filesystem::exists(partialName(base + "-d")));
}

TEST(CrashGuard, CommittedAndDestroyedOutputsAreNoLongerRegistered) {
  // 64 slots: 200 files opened and committed in turn must not exhaust them.
  const std::string base = dynobj::testing::scratchPath("");
  for (int i = 0; i < 200; i++) {
    AtomicFile f(base + std::to_string(i));
    f.stream() << i;
    if (i % 2) f.commit();
  }
  const int h = registerPartialOutput(base + "-last");
  EXPECT_GE(h, 0);
  unregisterPartialOutput(h);
  for (int i = 1; i < 200; i += 2) std::filesystem::remove(base + std::to_string(i));
}
