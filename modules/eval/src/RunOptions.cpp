// SPDX-License-Identifier: BSD-3-Clause
#include <algorithm>
#include <sstream>
#include <stdexcept>

#include "dynobj/eval/ExperimentRunner.h"

namespace dynobj::eval {
namespace {

std::vector<std::string> splitList(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

}  // namespace

const std::set<std::string>& RunOptions::modes() {
  static const std::set<std::string> m{"intensity", "gt-ego", "drift", "mrpt-distance"};
  return m;
}

std::string RunOptions::describe(const std::string& mode, const DriftParams& drift) {
  if (mode == "intensity") return "this detector, own intensity ego-motion (no odometry)";
  if (mode == "gt-ego") return "this detector, ground-truth ego-motion (upper bound)";
  if (mode == "drift") return "this detector, drifting odometry (" + drift.toString() + ")";
  if (mode == "mrpt-distance")
    return "MRPT CPointCloudFilterByDistance (defaults), ground-truth poses";
  return mode;
}

std::vector<std::string> RunOptions::parseModes(const std::string& list, bool have_poses) {
  std::vector<std::string> out = splitList(list);
  if (out.empty())
    out = have_poses ? std::vector<std::string>{"intensity", "gt-ego", "drift", "mrpt-distance"}
                     : std::vector<std::string>{"intensity"};
  for (const auto& m : out)
    if (!modes().count(m))
      throw std::invalid_argument("--modes: unknown mode '" + m +
                                  "' (intensity, gt-ego, drift, mrpt-distance)");
  return out;
}

std::set<int> RunOptions::evenlySpacedSweeps(int count, std::size_t frames) {
  std::set<int> out;
  const int first = std::min<int>(10, static_cast<int>(frames) - 1);
  for (int i = 0; i < count; i++)
    out.insert(first + static_cast<int>((static_cast<double>(i) + 0.5) / count *
                                        (static_cast<double>(frames) - first)));
  return out;
}

std::set<int> RunOptions::parseSweeps(const std::string& list, std::size_t frames) {
  std::set<int> out;
  for (const auto& item : splitList(list)) {
    std::size_t used = 0;
    int k = -1;
    try {
      k = std::stoi(item, &used);
    } catch (const std::exception&) {
    }
    if (used != item.size() || k < 0 || static_cast<std::size_t>(k) >= frames)
      throw std::invalid_argument("--overlay-sweeps: '" + item + "' is not a sweep index in [0, " +
                                  std::to_string(frames - 1) + "]");
    out.insert(k);
  }
  return out;
}

}  // namespace dynobj::eval
