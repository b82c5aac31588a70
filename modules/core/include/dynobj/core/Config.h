// SPDX-License-Identifier: BSD-3-Clause
// Strict INI readers: a value that does not parse is an error naming [section] key, never a silent
// 0.
#pragma once

#include <mrpt/config/CConfigFileBase.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace dynobj::core {

/// A bad or missing parameter. what() names the key (and the INI section when known).
class ParameterError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Throws ParameterError("<key>: <what>").
[[noreturn]] void throwParameterError(const std::string& key, const std::string& what);

/// Throws ParameterError unless lo <= value <= hi.
void requireInRange(const std::string& key, double value, double lo, double hi);

/// Throws ParameterError unless value > 0.
void requirePositive(const std::string& key, double value);

/// Throws ParameterError unless `value` is one of `choices` (the message lists them).
void requireOneOf(const std::string& key, const std::string& value,
                  const std::vector<std::string>& choices);

/// Edits (insertions, deletions, substitutions, swaps of two neighbours) between `a` and `b`,
/// ignoring case: the distance of a typo ("threshhold" -> "threshold": 1, "rnage" -> "range": 1).
std::size_t editDistance(const std::string& a, const std::string& b);

/// The name of `names` nearest to `word` when it is near enough to be what was meant (at most 2
/// edits, and a third of its length rounded up), else "". For "did you mean ...?" messages.
std::string closestName(const std::string& word, const std::vector<std::string>& names);

// Readers. A missing key returns `def`, or throws when `required`. A present key whose value does
// not parse completely (e.g. "12abc", "yes please") throws a ParameterError naming it.
double readDouble(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
                  const std::string& key, double def, bool required = false);
/// Reads degrees from the file and returns radians (MRPT convention).
double readDegrees(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   const std::string& key, double def_rad, bool required = false);
int readInt(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
            const std::string& key, int def, bool required = false);
bool readBool(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
              const std::string& key, bool def, bool required = false);
std::string readString(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
                       const std::string& key, const std::string& def, bool required = false);
/// A list written "a b c", "a, b, c" or "[a b c]"; empty when the key is absent.
std::vector<double> readDoubleList(const ::mrpt::config::CConfigFileBase& cfg,
                                   const std::string& section, const std::string& key,
                                   bool required = false);

}  // namespace dynobj::core
