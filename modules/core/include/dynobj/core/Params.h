// SPDX-License-Identifier: BSD-3-Clause
// Base of every stage's parameter struct: MRPT CLoadableOptions (INI sections; degrees in files,
// radians in memory) plus validate(), which names the bad key. Each struct lists its parameters
// once, in visit(); loading, saving and the INI keys all come from that list.
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

namespace dynobj::core {

/// Receives each parameter of a struct: its INI key and a reference to the field.
class ParamVisitor {
 public:
  virtual ~ParamVisitor() = default;
  virtual void value(const char* key, double& v) = 0;
  virtual void value(const char* key, int& v) = 0;
  virtual void value(const char* key, bool& v) = 0;
  virtual void value(const char* key, std::string& v) = 0;
  /// An angle: radians in memory, degrees in the INI file.
  virtual void degrees(const char* key, double& v) = 0;
};

struct StageParams : public ::mrpt::config::CLoadableOptions {
  /// Calls `v` once per parameter (field name = INI key).
  virtual void visit(ParamVisitor& v) = 0;
  /// Throws ParameterError("<key>: <problem>") for the first invalid value.
  virtual void validate() const = 0;
  /// Its INI keys, in visit() order (what a strict INI reader accepts in its section).
  std::vector<std::string> keys() const;

  /// Reads every key present in `section` (absent keys keep their value), then validate().
  void loadFromConfigFile(const ::mrpt::config::CConfigFileBase& c,
                          const std::string& section) override;
  void saveToConfigFile(::mrpt::config::CConfigFileBase& c,
                        const std::string& section) const override;
};

}  // namespace dynobj::core
