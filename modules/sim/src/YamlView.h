// SPDX-License-Identifier: BSD-3-Clause
// Internal: a read-only view of an MRPT yaml node with strict, path-naming accessors, so that a
// bad scenario file says e.g. "hall.yaml: actors[3].trajectory.speed: 'fast' is not a number".
#pragma once

#include <mrpt/containers/yaml.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace dynobj::sim::detail {

class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class YamlView {
 public:
  using Node = ::mrpt::containers::yaml::node_t;
  YamlView(const Node* node, std::string path) : node_(node), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  bool isMap() const { return node_ && node_->isMap(); }
  bool isSequence() const { return node_ && node_->isSequence(); }
  bool has(const std::string& key) const { return find(key) != nullptr; }

  YamlView child(const std::string& key) const;  ///< throws if missing
  std::vector<YamlView> items() const;           ///< sequence elements; throws if not a sequence
  std::vector<YamlView> seq(const std::string& key) const { return child(key).items(); }

  std::string scalar() const;  ///< this node as text
  double number() const;
  std::vector<double> numbers() const;  ///< a sequence of numbers

  std::string str(const std::string& key, const std::string& def) const;
  double num(const std::string& key, double def) const;
  double numRequired(const std::string& key) const { return child(key).number(); }
  bool flag(const std::string& key, bool def) const;
  std::vector<double> nums(const std::string& key, std::size_t expected_size = 0) const;

  /// Throws unless every key of this map is in `allowed` (catches typos in scenario files).
  void onlyKeys(const std::vector<std::string>& allowed) const;

  [[noreturn]] void fail(const std::string& what) const;

 private:
  const Node* find(const std::string& key) const;
  const Node* node_;
  std::string path_;
};

}  // namespace dynobj::sim::detail
