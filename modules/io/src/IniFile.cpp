// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/IniFile.h"

#include <dynobj/core/Config.h>
#include <dynobj/core/DynamicObjectDetector.h>
#include <mrpt/config/CConfigFile.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>

namespace dynobj::io {
namespace {

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

bool sameName(const std::string& a, const std::string& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

bool startsWith(const std::string& s, const std::string& prefix) {
  return s.size() >= prefix.size() && sameName(s.substr(0, prefix.size()), prefix);
}

bool contains(const std::vector<std::string>& names, const std::string& n) {
  return std::any_of(names.begin(), names.end(), [&](const auto& k) { return sameName(k, n); });
}

}  // namespace

IniFile::IniFile(const std::string& path, const std::string& what) : path_(path) {
  if (!std::filesystem::exists(path))
    throw core::ParameterError(what + " '" + path + "' does not exist");
  if (!std::filesystem::is_regular_file(path))
    throw core::ParameterError(what + " '" + path + "' is not a file");
  std::ifstream in(path);
  if (!in) throw core::ParameterError("cannot read " + what + " '" + path + "'");
  std::string text, section;
  for (int n = 1; std::getline(in, text); n++) {
    const std::string t = trim(text);
    // Comments, and MRPT's directives (@define, @include): not the reader's keys.
    if (t.empty() || t[0] == ';' || t[0] == '#' || t[0] == '@' || t.rfind("//", 0) == 0) continue;
    if (t[0] == '[') {
      const auto close = t.find(']');
      section = trim(t.substr(1, close == std::string::npos ? std::string::npos : close - 1));
      lines_.push_back({Line::Header, n, section, ""});
    } else if (const auto eq = t.find('='); eq != std::string::npos) {
      lines_.push_back({Line::Key, n, section, trim(t.substr(0, eq))});
    } else {
      lines_.push_back({Line::Other, n, section, t});
    }
  }
  cfg_ = std::make_unique<mrpt::config::CConfigFile>(path);
}

IniFile::~IniFile() = default;

const mrpt::config::CConfigFileBase& IniFile::config() const {
  return *cfg_;
}

void IniFile::expect(const std::string& section, const std::vector<std::string>& keys) {
  known_.emplace_back(section, keys);
}

void IniFile::expectDetector(const std::string& prefix) {
  core::DetectorParams().forEachStage([&](const char* name, const core::StageParams& stage) {
    expect(prefix + name, stage.keys());
  });
}

void IniFile::check(const std::string& own) const {
  std::vector<std::string> sections;
  for (const auto& [s, keys] : known_) sections.push_back(s);
  const auto keysOf = [&](const std::string& s) -> const std::vector<std::string>* {
    for (const auto& [name, keys] : known_)
      if (sameName(name, s)) return &keys;
    return nullptr;
  };
  std::string problems;
  const auto problem = [&](int line, const std::string& what) {
    problems += (problems.empty() ? "" : "\n") + path_ + ":" + std::to_string(line) + ": " + what;
  };
  bool checked = own.empty();  // keys before the first header: every one when all is ours
  const std::vector<std::string>* keys = nullptr;
  for (const Line& l : lines_) {
    if (l.kind == Line::Header) {
      keys = keysOf(l.section);
      const std::string near = keys ? "" : core::closestName(l.section, sections);
      checked = keys || own.empty() || startsWith(l.section, own) || !near.empty();
      if (checked && !keys) {
        std::string list;
        for (const auto& s : sections) list += (list.empty() ? "[" : ", [") + s + "]";
        problem(l.line,
                "unknown section [" + l.section + "] " +
                    (near.empty() ? "(known: " + list + ")" : "(did you mean [" + near + "]?)"));
      }
      continue;
    }
    if (!checked) continue;
    if (!keys && !l.section.empty()) continue;  // an unknown section: reported once, above
    if (l.kind == Line::Other) {
      problem(l.line, "'" + l.key + "' is neither '[section]' nor 'key = value'");
      continue;
    }
    if (!keys) {
      problem(l.line, "key '" + l.key + "' outside any section");
      continue;
    }
    if (contains(*keys, l.key)) continue;
    std::string hint;
    if (const std::string near = core::closestName(l.key, *keys); !near.empty()) {
      hint = " (did you mean '" + near + "'?)";
    } else {
      for (const auto& [s, other] : known_)
        if (contains(other, l.key)) {
          hint = " (it is a key of [" + s + "])";
          break;
        }
    }
    problem(l.line, "unknown key '" + l.key + "' in [" + l.section + "]" + hint);
  }
  if (!problems.empty()) throw core::ParameterError(problems);
}

core::DetectorParams loadDetectorParams(
    const std::string& ini, const std::string& section,
    std::initializer_list<std::pair<const char*, core::StageParams*>> extra) {
  core::DetectorParams p;
  if (ini.empty()) return p;
  IniFile file(ini, "config file");
  file.expectDetector(section);
  for (const auto& [name, params] : extra) file.expect(name, params->keys());
  file.check(section);
  p.load(file.config(), section);
  for (const auto& [name, params] : extra) params->loadFromConfigFile(file.config(), name);
  return p;
}

}  // namespace dynobj::io
