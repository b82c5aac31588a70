// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/TimingStats.h"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace dynobj::eval {

const std::vector<std::string>& TimingStats::stages() {
  static const std::vector<std::string> names{"ground",         "foreground",  "ego-motion",
                                              "clustering",     "association", "movement",
                                              "region growing", "hindsight",   "total"};
  return names;
}

void TimingStats::add(const core::StageTimings& t) {
  const double v[] = {t.ground,   t.foreground,     t.ego_motion, t.clustering, t.association,
                      t.movement, t.region_growing, t.hindsight,  t.total};
  static_assert(std::size(v) == 9, "one time per stage");
  for (std::size_t i = 0; i < std::size(v); i++) ms_[stages()[i]].push_back(v[i]);
  frames_++;
}

double TimingStats::percentile(const std::string& stage, double q) const {
  const auto it = ms_.find(stage);
  if (it == ms_.end()) throw std::invalid_argument("TimingStats: no stage '" + stage + "'");
  std::vector<double> v = it->second;
  if (v.empty()) return 0;
  const auto k = static_cast<std::size_t>(q / 100.0 * static_cast<double>(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

void TimingStats::print(std::ostream& out) const {
  char line[96];
  out << "  stage              median ms   p99 ms\n";
  for (const std::string& s : stages()) {
    if (!ms_.count(s)) continue;
    std::snprintf(line, sizeof(line), "  %-18s %9.3f %8.3f\n", s.c_str(), percentile(s, 50),
                  percentile(s, 99));
    out << line;
  }
}

}  // namespace dynobj::eval
