// SPDX-License-Identifier: BSD-3-Clause
// Strict INI files, the one mechanism of every INI reader (detector configs, sensor presets,
// dynobj-mapclean's [mapclean], icp-slam-dynobj's [DynamicObjects]). MRPT's CConfigFile reads the
// values (core/Config.h's readers take it) but ignores a key or a section nobody asks for, and
// keeps no line numbers: IniFile scans the file's text for its section headers and keys with their
// lines, and check() rejects each one the reader did not declare, e.g.
//   dynobj.ini:12: unknown key 'threshhold' in [foreground] (did you mean 'threshold'?)
//   dynobj.ini:7: unknown section [forground] (did you mean [foreground]?)
// Names compare without case, as MRPT reads them.
#pragma once

#include <initializer_list>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace mrpt::config {
class CConfigFileBase;
class CConfigFile;
}  // namespace mrpt::config
namespace dynobj::core {
struct DetectorParams;
struct StageParams;
}  // namespace dynobj::core

namespace dynobj::io {

class IniFile {
 public:
  /// Reads `path` (`what` names it in messages, e.g. "config file"); throws core::ParameterError
  /// when it does not exist or is not a file.
  explicit IniFile(const std::string& path, const std::string& what = "config file");
  ~IniFile();
  IniFile(const IniFile&) = delete;
  IniFile& operator=(const IniFile&) = delete;

  const std::string& path() const { return path_; }
  /// The values, as MRPT reads them.
  const mrpt::config::CConfigFileBase& config() const;

  /// Declares a section the reader reads, and its keys.
  void expect(const std::string& section, const std::vector<std::string>& keys);
  /// Declares every detector stage's section, <prefix><stage> (core::DetectorParams).
  void expectDetector(const std::string& prefix = "");

  /// Throws core::ParameterError with one line per key or section the reader did not declare
  /// ("<file>:<line>: unknown ..."), naming the nearest declared one when it is near. With `own`
  /// set, only the sections whose name starts with it, or is near a declared one, belong to the
  /// reader; the others (another application's, in a file they share: icp-slam's) are left alone.
  void check(const std::string& own = "") const;

  /// A line of the file that is not a comment: a section header, a key, or neither.
  struct Line {
    enum Kind { Header, Key, Other } kind = Key;
    int line = 0;
    std::string section;  ///< the header's name, or the section the line is in
    std::string key;      ///< Key: the key; Other: the line's text
  };
  const std::vector<Line>& lines() const { return lines_; }

 private:
  std::string path_;
  std::unique_ptr<mrpt::config::CConfigFile> cfg_;
  std::vector<Line> lines_;
  std::vector<std::pair<std::string, std::vector<std::string>>> known_;
};

/// The detector's parameters from `ini` (defaults when empty), sections prefixed by `section`,
/// and those of `extra` (section name, its parameters) from the same file: what every tool's -c
/// and the Python module's config read. Throws core::ParameterError when the file does not exist,
/// or a value, key or section is bad ("file:line: unknown key ..."). With a prefix, sections that
/// neither start with it nor resemble one of ours are left alone.
core::DetectorParams loadDetectorParams(
    const std::string& ini, const std::string& section = "",
    std::initializer_list<std::pair<const char*, core::StageParams*>> extra = {});

}  // namespace dynobj::io
