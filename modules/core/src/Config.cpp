// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/Config.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>

namespace dynobj::core {
namespace {

std::string qualified(const std::string& section, const std::string& key) {
  return "[" + section + "] " + key;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return {};
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

/// Strips a trailing "; comment" or "# comment" (MRPT INI files allow them after values).
std::string stripComment(const std::string& s) {
  const auto p = s.find_first_of(";#");
  return trim(p == std::string::npos ? s : s.substr(0, p));
}

/// The raw value, or nullopt-like empty flag when absent.
bool rawValue(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
              const std::string& key, bool required, std::string& out) {
  if (!cfg.keyExists(section, key)) {
    if (required) throwParameterError(qualified(section, key), "required key is missing");
    return false;
  }
  out = stripComment(cfg.read_string(section, key, ""));
  if (out.empty()) {
    if (required) throwParameterError(qualified(section, key), "required key has no value");
    return false;
  }
  return true;
}

double parseDouble(const std::string& where, const std::string& text) {
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    throwParameterError(where, "'" + text + "' is not a number");
  }
  if (used != text.size()) throwParameterError(where, "'" + text + "' is not a number");
  if (!std::isfinite(v)) throwParameterError(where, "'" + text + "' is not finite");
  return v;
}

}  // namespace

std::size_t editDistance(const std::string& a, const std::string& b) {
  const auto lower = [](char c) { return std::tolower(static_cast<unsigned char>(c)); };
  const std::size_t n = a.size(), m = b.size();
  // Optimal string alignment: Levenshtein plus the swap of two neighbouring characters.
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1, 0));
  for (std::size_t i = 0; i <= n; i++) d[i][0] = i;
  for (std::size_t j = 0; j <= m; j++) d[0][j] = j;
  for (std::size_t i = 1; i <= n; i++)
    for (std::size_t j = 1; j <= m; j++) {
      const std::size_t cost = lower(a[i - 1]) == lower(b[j - 1]) ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && lower(a[i - 1]) == lower(b[j - 2]) &&
          lower(a[i - 2]) == lower(b[j - 1]))
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
    }
  return d[n][m];
}

std::string closestName(const std::string& word, const std::vector<std::string>& names) {
  std::string best;
  std::size_t best_d = std::min<std::size_t>(2, (word.size() + 2) / 3);
  for (const std::string& n : names) {
    const std::size_t d = editDistance(word, n);
    if (d <= best_d && (best.empty() || d < best_d)) best = n, best_d = d;
  }
  return best;
}

void throwParameterError(const std::string& key, const std::string& what) {
  throw ParameterError(key + ": " + what);
}

void requireInRange(const std::string& key, double value, double lo, double hi) {
  if (!(value >= lo && value <= hi)) {
    std::ostringstream ss;
    ss << "value " << value << " is outside [" << lo << ", " << hi << "]";
    throwParameterError(key, ss.str());
  }
}

void requireOneOf(const std::string& key, const std::string& value,
                  const std::vector<std::string>& choices) {
  if (std::find(choices.begin(), choices.end(), value) != choices.end()) return;
  std::string list;
  for (const std::string& c : choices) list += (list.empty() ? "" : ", ") + c;
  throwParameterError(key, "'" + value + "' is not one of: " + list);
}

void requirePositive(const std::string& key, double value) {
  if (!(value > 0)) {
    std::ostringstream ss;
    ss << "value " << value << " must be > 0";
    throwParameterError(key, ss.str());
  }
}

double readDouble(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
                  const std::string& key, double def, bool required) {
  std::string raw;
  if (!rawValue(cfg, section, key, required, raw)) return def;
  return parseDouble(qualified(section, key), raw);
}

double readDegrees(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
                   const std::string& key, double def_rad, bool required) {
  std::string raw;
  if (!rawValue(cfg, section, key, required, raw)) return def_rad;
  return parseDouble(qualified(section, key), raw) * M_PI / 180.0;
}

int readInt(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
            const std::string& key, int def, bool required) {
  std::string raw;
  if (!rawValue(cfg, section, key, required, raw)) return def;
  const double v = parseDouble(qualified(section, key), raw);
  if (v != std::floor(v) || std::abs(v) > 2e9)
    throwParameterError(qualified(section, key), "'" + raw + "' is not an integer");
  return static_cast<int>(v);
}

bool readBool(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
              const std::string& key, bool def, bool required) {
  std::string raw;
  if (!rawValue(cfg, section, key, required, raw)) return def;
  std::string v = raw;
  std::transform(v.begin(), v.end(), v.begin(), [](unsigned char c) { return std::tolower(c); });
  if (v == "1" || v == "true" || v == "yes" || v == "on") return true;
  if (v == "0" || v == "false" || v == "no" || v == "off") return false;
  throwParameterError(qualified(section, key), "'" + raw + "' is not a boolean (true/false/1/0)");
}

std::string readString(const ::mrpt::config::CConfigFileBase& cfg, const std::string& section,
                       const std::string& key, const std::string& def, bool required) {
  std::string raw;
  if (!rawValue(cfg, section, key, required, raw)) return def;
  return raw;
}

std::vector<double> readDoubleList(const ::mrpt::config::CConfigFileBase& cfg,
                                   const std::string& section, const std::string& key,
                                   bool required) {
  std::string raw;
  if (!rawValue(cfg, section, key, required, raw)) return {};
  std::string cleaned = raw;
  for (char& c : cleaned)
    if (c == '[' || c == ']' || c == ',') c = ' ';
  std::istringstream ss(cleaned);
  std::vector<double> out;
  std::string token;
  while (ss >> token) out.push_back(parseDouble(qualified(section, key), token));
  return out;
}

}  // namespace dynobj::core
