// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/Params.h"

#include <cmath>

#include "dynobj/core/Config.h"

namespace dynobj::core {
namespace {

class Reader : public ParamVisitor {
 public:
  Reader(const ::mrpt::config::CConfigFileBase& c, const std::string& s) : c_(c), s_(s) {}
  void value(const char* key, double& v) override { v = readDouble(c_, s_, key, v); }
  void value(const char* key, int& v) override { v = readInt(c_, s_, key, v); }
  void value(const char* key, bool& v) override { v = readBool(c_, s_, key, v); }
  void value(const char* key, std::string& v) override { v = readString(c_, s_, key, v); }
  void degrees(const char* key, double& v) override { v = readDegrees(c_, s_, key, v); }

 private:
  const ::mrpt::config::CConfigFileBase& c_;
  const std::string& s_;
};

class Writer : public ParamVisitor {
 public:
  Writer(::mrpt::config::CConfigFileBase& c, const std::string& s) : c_(c), s_(s) {}
  void value(const char* key, double& v) override { c_.write(s_, key, v); }
  void value(const char* key, int& v) override { c_.write(s_, key, v); }
  void value(const char* key, bool& v) override { c_.write(s_, key, v); }
  void value(const char* key, std::string& v) override { c_.write(s_, key, v); }
  void degrees(const char* key, double& v) override { c_.write(s_, key, v * 180.0 / M_PI); }

 private:
  ::mrpt::config::CConfigFileBase& c_;
  const std::string& s_;
};

class KeyCollector : public ParamVisitor {
 public:
  void value(const char* key, double&) override { keys.emplace_back(key); }
  void value(const char* key, int&) override { keys.emplace_back(key); }
  void value(const char* key, bool&) override { keys.emplace_back(key); }
  void value(const char* key, std::string&) override { keys.emplace_back(key); }
  void degrees(const char* key, double&) override { keys.emplace_back(key); }
  std::vector<std::string> keys;
};

}  // namespace

std::vector<std::string> StageParams::keys() const {
  KeyCollector k;
  const_cast<StageParams*>(this)->visit(k);  // the collector only reads the names
  return k.keys;
}

void StageParams::loadFromConfigFile(const ::mrpt::config::CConfigFileBase& c,
                                     const std::string& section) {
  Reader r(c, section);
  visit(r);
  validate();
}

void StageParams::saveToConfigFile(::mrpt::config::CConfigFileBase& c,
                                   const std::string& section) const {
  Writer w(c, section);
  const_cast<StageParams*>(this)->visit(w);  // the writer only reads the fields
}

}  // namespace dynobj::core
