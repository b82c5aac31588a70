// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/AtomicFile.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/system/filesystem.h>

#include <fstream>

using namespace dynobj::io;

TEST(AtomicFile, CommitRenamesIntoPlaceAndLeavesNoPartial) {
  const std::string p = dynobj::testing::scratchPath(".txt");
  writeFileAtomically(p, "abc");
  std::ifstream in(p);
  std::string s;
  in >> s;
  EXPECT_EQ(s, "abc");
  EXPECT_FALSE(::mrpt::system::fileExists(partialName(p)));
}

TEST(AtomicFile, UncommittedFileIsRemovedAndNothingAppearsUnderTheFinalName) {
  const std::string p = dynobj::testing::scratchPath(".txt");
  {
    AtomicFile f(p);
    f.stream() << "half";
    EXPECT_TRUE(::mrpt::system::fileExists(partialName(p)));
    EXPECT_FALSE(::mrpt::system::fileExists(p));
  }  // an exception or an error path: no commit()
  EXPECT_FALSE(::mrpt::system::fileExists(partialName(p)));
  EXPECT_FALSE(::mrpt::system::fileExists(p));
}

TEST(AtomicFile, UnwritableFolderIsAnErrorNamingTheFileAndTheCause) {
  try {
    writeFileAtomically("/nonexistent-dir/x.txt", "abc");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(),
                 "cannot write '/nonexistent-dir/x.txt': the folder '/nonexistent-dir' does not "
                 "exist");
  }
  EXPECT_EQ(dynobj::io::cannotWriteMessage("/proc/version/x"),
            "cannot write '/proc/version/x': '/proc/version' is not a folder");
}
