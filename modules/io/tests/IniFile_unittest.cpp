// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/core/SensorModel.h>
#include <dynobj/io/IniFile.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

using dynobj::core::ParameterError;
using dynobj::io::IniFile;

namespace {

/// A temporary INI file, removed at the end of the test.
class TempIni {
 public:
  explicit TempIni(const std::string& text)
      : path_((std::filesystem::temp_directory_path() /
               ("dynobj-inifile-" + std::to_string(getpid()) + "-" + std::to_string(count_++) +
                ".ini"))
                  .string()) {
    std::ofstream(path_) << text;
  }
  ~TempIni() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  static inline int count_ = 0;
};

/// check()'s message, or "" when it passes.
std::string problems(const IniFile& f, const std::string& own = "") {
  try {
    f.check(own);
  } catch (const ParameterError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(IniFile, UnknownKeyNamesFileLineAndNearestKey) {
  const TempIni ini("; comment\n[foreground]\nthreshold = 14\nthreshhold = 20\n");
  IniFile f(ini.path());
  f.expectDetector();
  EXPECT_EQ(
      problems(f),
      ini.path() + ":4: unknown key 'threshhold' in [foreground] (did you mean 'threshold'?)");
}

TEST(IniFile, UnknownSectionNamesTheNearestSection) {
  const TempIni ini("[forground]\nthreshold = 14\n");
  IniFile f(ini.path());
  f.expectDetector();
  EXPECT_EQ(problems(f),
            ini.path() + ":1: unknown section [forground] (did you mean [foreground]?)");
}

TEST(IniFile, KeyOfAnotherSectionAndOddLinesAreNamed) {
  const TempIni ini("stray = 1\n[movement]\nkernel_half_width = 3\nno equals sign\n[xyz]\na = 1\n");
  IniFile f(ini.path());
  f.expectDetector();
  const std::string p = problems(f);
  EXPECT_NE(p.find(":1: key 'stray' outside any section"), std::string::npos) << p;
  EXPECT_NE(p.find(":3: unknown key 'kernel_half_width' in [movement] (it is a key of "
                   "[foreground])"),
            std::string::npos)
      << p;
  EXPECT_NE(p.find(":4: 'no equals sign' is neither '[section]' nor 'key = value'"),
            std::string::npos)
      << p;
  EXPECT_NE(p.find(":5: unknown section [xyz] (known: [foreground], "), std::string::npos) << p;
  EXPECT_EQ(p.find("'a'"), std::string::npos) << "keys of an unknown section: reported once";
}

TEST(IniFile, NamesCompareWithoutCaseAndSectionsMayRepeat) {
  const TempIni ini(
      "[Foreground]\nThreshold = 14\n[movement]\nwindow = 5\n[foreground]\nabsolute = "
      "true\n");
  IniFile f(ini.path());
  f.expectDetector();
  EXPECT_EQ(problems(f), "");
}

TEST(IniFile, WithAPrefixOnlyItsOwnSectionsAreChecked) {
  // A stock icp-slam file: [ICP] and its keys are icp-slam's; [DynamicObjects*] are ours, and a
  // section that resembles ours is a typo.
  const TempIni ini(
      "[ICP]\nmaxIterations = 80\n[DynamicObjects]\nenabeld = true\n[DynamicObjects_foreground]\n"
      "threshold = 3\n[DynamicObject_ground]\nmax_slope = 5\n");
  IniFile f(ini.path());
  f.expect("DynamicObjects", {"enabled", "mode"});
  f.expectDetector("DynamicObjects_");
  const std::string p = problems(f, "DynamicObjects");
  EXPECT_EQ(p.find("ICP"), std::string::npos) << p;
  EXPECT_NE(p.find(":4: unknown key 'enabeld' in [DynamicObjects] (did you mean 'enabled'?)"),
            std::string::npos)
      << p;
  EXPECT_NE(p.find(":7: unknown section [DynamicObject_ground] (did you mean "
                   "[DynamicObjects_ground]?)"),
            std::string::npos)
      << p;
}

TEST(IniFile, MissingFileIsNamed) {
  try {
    IniFile f("/nonexistent/x.ini", "sensor file");
    FAIL();
  } catch (const ParameterError& e) {
    EXPECT_STREQ(e.what(), "sensor file '/nonexistent/x.ini' does not exist");
  }
}

TEST(IniFile, EveryShippedFilePassesItsReader) {
  namespace fs = std::filesystem;
  const std::string share = DYNOBJ_SHARE_DIR;
  for (const auto& e : fs::directory_iterator(share + "/sensors")) {
    SCOPED_TRACE(e.path().string());
    IniFile f(e.path().string(), "sensor file");
    f.expect("sensor", dynobj::core::SensorModel::iniKeys());
    EXPECT_EQ(problems(f), "");
  }
  for (const char* name : {"dynobj.ini", "advanced.ini", "dynobj-os0-128-2048.ini"}) {
    IniFile f(share + "/config/" + name);
    f.expectDetector();
    EXPECT_EQ(problems(f), "") << name;
  }
  for (const char* name : {"icp-slam-hall.ini", "icp-slam-dynobj-hall.ini"}) {
    IniFile f(share + "/config/" + name);
    f.expect("DynamicObjects", {"enabled", "mode", "sensor_label", "sensor", "allow_none"});
    f.expectDetector("DynamicObjects_");
    EXPECT_EQ(problems(f, "DynamicObjects"), "") << name;
  }
}

TEST(Config, EditDistanceAndClosestName) {
  using dynobj::core::closestName;
  using dynobj::core::editDistance;
  EXPECT_EQ(editDistance("threshhold", "threshold"), 1u);
  EXPECT_EQ(editDistance("max_rnage", "max_range"), 1u);  // two neighbours swapped
  EXPECT_EQ(editDistance("Voxel_Size", "voxel_size"), 0u);
  EXPECT_EQ(editDistance("", "abc"), 3u);
  EXPECT_EQ(closestName("enabeld", {"mode", "enabled", "sensor"}), "enabled");
  EXPECT_EQ(closestName("voxel_sise", {"voxel_size", "box_margin"}), "voxel_size");
  EXPECT_EQ(closestName("colour", {"rows", "cols"}), "");  // too far to be a typo of either
}
