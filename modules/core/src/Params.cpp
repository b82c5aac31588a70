// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/Params.h"

#include <cmath>

#include "dynobj/core/Config.h"

namespace dynobj::core {
namespace {

class Reader : public ParamVisitor {
 public:
  Reader(const ::mrpt::config::CConfigFileBase& c, const std::string& s) : c_(c), s_(s) {}
  void real(const char* key, double& v, const Range&) override { v = readDouble(c_, s_, key, v); }
  void integer(const char* key, int& v, const Range&) override { v = readInt(c_, s_, key, v); }
  void flag(const char* key, bool& v) override { v = readBool(c_, s_, key, v); }
  void text(const char* key, std::string& v) override { v = readString(c_, s_, key, v); }
  void angle(const char* key, double& v, const Range&) override { v = readDegrees(c_, s_, key, v); }

 private:
  const ::mrpt::config::CConfigFileBase& c_;
  const std::string& s_;
};

class Writer : public ParamVisitor {
 public:
  Writer(::mrpt::config::CConfigFileBase& c, const std::string& s) : c_(c), s_(s) {}
  void real(const char* key, double& v, const Range&) override { c_.write(s_, key, v); }
  void integer(const char* key, int& v, const Range&) override { c_.write(s_, key, v); }
  void flag(const char* key, bool& v) override { c_.write(s_, key, v); }
  void text(const char* key, std::string& v) override { c_.write(s_, key, v); }
  void angle(const char* key, double& v, const Range&) override {
    c_.write(s_, key, v * 180.0 / M_PI);
  }

 private:
  ::mrpt::config::CConfigFileBase& c_;
  const std::string& s_;
};

class KeyCollector : public ParamVisitor {
 public:
  std::vector<std::string> keys;

 protected:
  void real(const char* key, double&, const Range&) override { keys.emplace_back(key); }
  void integer(const char* key, int&, const Range&) override { keys.emplace_back(key); }
  void flag(const char* key, bool&) override { keys.emplace_back(key); }
  void text(const char* key, std::string&) override { keys.emplace_back(key); }
  void angle(const char* key, double&, const Range&) override { keys.emplace_back(key); }
};

/// Throws at the first number outside its range.
class RangeCheck : public ParamVisitor {
 protected:
  void real(const char* key, double& v, const Range& r) override { check(key, v, r); }
  void integer(const char* key, int& v, const Range& r) override { check(key, v, r); }
  void flag(const char*, bool&) override {}
  void text(const char*, std::string&) override {}
  void angle(const char* key, double& v, const Range& r) override { check(key, v, r); }

 private:
  static void check(const char* key, double v, const Range& r) {
    if (r.positive)
      requirePositive(key, v);
    else if (r.lo > -HUGE_VAL || r.hi < HUGE_VAL)
      requireInRange(key, v, r.lo, r.hi);
  }
};

}  // namespace

std::vector<std::string> StageParams::keys() const {
  KeyCollector k;
  const_cast<StageParams*>(this)->visit(k);  // the collector only reads the names
  return k.keys;
}

void StageParams::validate() const {
  RangeCheck check;
  const_cast<StageParams*>(this)->visit(check);  // the check only reads the fields
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
