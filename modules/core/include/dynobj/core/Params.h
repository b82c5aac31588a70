// SPDX-License-Identifier: BSD-3-Clause
// Base of every stage's parameter struct: MRPT CLoadableOptions (INI sections; degrees in files,
// radians in memory) plus validate(), which names the bad key. Each struct lists its parameters
// once, in visit(), with the values each may take; loading, saving, checking and the INI keys all
// come from that list.
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <cmath>
#include <string>
#include <vector>

namespace dynobj::core {

/// The values a number may take: lo <= v <= hi, or v > 0 (`positive`). The default: any.
struct Range {
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  bool positive = false;
};
/// v > 0.
inline constexpr Range kPositive{0, HUGE_VAL, true};

/// Receives each parameter of a struct: its INI key, a reference to the field and the values it
/// may take (validate() checks them).
class ParamVisitor {
 public:
  virtual ~ParamVisitor() = default;
  void value(const char* key, double& v, Range r = {}) { real(key, v, r); }
  void value(const char* key, int& v, Range r = {}) { integer(key, v, r); }
  void value(const char* key, bool& v) { flag(key, v); }
  void value(const char* key, std::string& v) { text(key, v); }
  /// An angle: radians in memory (and in its range), degrees in the INI file.
  void degrees(const char* key, double& v, Range r = {}) { angle(key, v, r); }

 protected:
  virtual void real(const char* key, double& v, const Range& r) = 0;
  virtual void integer(const char* key, int& v, const Range& r) = 0;
  virtual void flag(const char* key, bool& v) = 0;
  virtual void text(const char* key, std::string& v) = 0;
  virtual void angle(const char* key, double& v, const Range& r) = 0;
};

struct StageParams : public ::mrpt::config::CLoadableOptions {
  /// Calls `v` once per parameter (field name = INI key), with its range.
  virtual void visit(ParamVisitor& v) = 0;
  /// Throws ParameterError("<key>: <problem>") for the first value outside its range; a struct
  /// whose keys depend on each other adds those rules after this.
  virtual void validate() const;
  /// Its INI keys, in visit() order (what a strict INI reader accepts in its section).
  std::vector<std::string> keys() const;

  /// Reads every key present in `section` (absent keys keep their value), then validate().
  void loadFromConfigFile(const ::mrpt::config::CConfigFileBase& c,
                          const std::string& section) override;
  void saveToConfigFile(::mrpt::config::CConfigFileBase& c,
                        const std::string& section) const override;
};

}  // namespace dynobj::core
