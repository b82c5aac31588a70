// SPDX-License-Identifier: BSD-3-Clause
#include "YamlView.h"

#include <algorithm>
#include <cmath>

namespace dynobj::sim::detail {

void YamlView::fail(const std::string& what) const {
  throw ScenarioError((path_.empty() ? std::string("(root)") : path_) + ": " + what);
}

const YamlView::Node* YamlView::find(const std::string& key) const {
  if (!node_ || !node_->isMap()) return nullptr;
  for (const auto& [k, v] : node_->asMap())
    if (k.isScalar() && k.as<std::string>() == key) return &v;
  return nullptr;
}

YamlView YamlView::child(const std::string& key) const {
  const Node* n = find(key);
  const std::string p = path_.empty() ? key : path_ + "." + key;
  if (!n) YamlView(nullptr, p).fail("required key is missing");
  return YamlView(n, p);
}

std::vector<YamlView> YamlView::items() const {
  if (!isSequence()) fail("expected a list");
  std::vector<YamlView> out;
  const auto& s = node_->asSequence();
  for (std::size_t i = 0; i < s.size(); i++)
    out.emplace_back(&s[i], path_ + "[" + std::to_string(i) + "]");
  return out;
}

std::string YamlView::scalar() const {
  if (!node_ || !node_->isScalar()) fail("expected a single value");
  return node_->as<std::string>();
}

double YamlView::number() const {
  const std::string s = scalar();
  std::size_t used = 0;
  double v = 0;
  try {
    v = std::stod(s, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != s.size() || !std::isfinite(v)) fail("'" + s + "' is not a number");
  return v;
}

std::vector<double> YamlView::numbers() const {
  std::vector<double> out;
  for (const auto& it : items()) out.push_back(it.number());
  return out;
}

std::string YamlView::str(const std::string& key, const std::string& def) const {
  return has(key) ? child(key).scalar() : def;
}

double YamlView::num(const std::string& key, double def) const {
  return has(key) ? child(key).number() : def;
}

bool YamlView::flag(const std::string& key, bool def) const {
  if (!has(key)) return def;
  const YamlView c = child(key);
  std::string s = c.scalar();
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char ch) { return std::tolower(ch); });
  if (s == "true" || s == "1" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "0" || s == "no" || s == "off") return false;
  c.fail("'" + s + "' is not a boolean");
}

std::vector<double> YamlView::nums(const std::string& key, std::size_t expected_size) const {
  const YamlView c = child(key);
  auto v = c.numbers();
  if (expected_size && v.size() != expected_size)
    c.fail("expected " + std::to_string(expected_size) + " numbers, got " +
           std::to_string(v.size()));
  return v;
}

void YamlView::onlyKeys(const std::vector<std::string>& allowed) const {
  if (!isMap()) fail("expected a map of key: value");
  for (const auto& [k, v] : node_->asMap()) {
    const std::string key = k.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      fail("unknown key '" + key + "' (allowed: " + list + ")");
    }
  }
}

}  // namespace dynobj::sim::detail
