// SPDX-License-Identifier: BSD-3-Clause
// Benchmark: row recovery per sweep (core::recoverRows, no sensor model) on the simulated firing
// patterns of the row recovery tests, the same points stored two ways side by side: in raw firing
// order (rule 3, firing cycle) and laser by laser (rule 2, firing order). Median of 7 runs.
//   build/tests/row_recovery_bench
#include <dynobj/core/RowRecovery.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "UnorderedSweep.h"

namespace {

/// Median time [ms] of recoverRows on `cloud`; `source` = the rule, or "refused" when none applies.
double medianMs(const dynobj::core::PointCloud& cloud, std::string& source) {
  std::vector<double> ms;
  for (int k = 0; k < 7; k++) {
    dynobj::core::PointCloud c = cloud;
    const auto t0 = std::chrono::steady_clock::now();
    try {
      source = toString(dynobj::core::recoverRows(c, std::nullopt).source);
    } catch (const std::invalid_argument&) {
      source = "refused";
    }
    ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  std::sort(ms.begin(), ms.end());
  return ms[3];
}

}  // namespace

int main() {
  std::printf("%-8s %8s  %-28s %-28s\n", "pattern", "points", "raw firing order (rule 3)",
              "laser by laser (rule 2)");
  for (const auto& p : {dynobj::test::vlp16Pattern(), dynobj::test::hdl32Pattern(),
                        dynobj::test::hdl64Pattern(), dynobj::test::vls128Pattern()}) {
    std::vector<int> laser;
    const dynobj::core::PointCloud raw = dynobj::test::rawFiringSweep(p, laser, 360.0);
    // The same points laser by laser, top laser first (how KITTI stores a sweep), each laser's in
    // firing order.
    std::vector<int> ids(p.elevation_deg.size());
    for (std::size_t l = 0; l < ids.size(); l++) ids[l] = static_cast<int>(l);
    std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) {
      return p.elevation_deg[static_cast<std::size_t>(a)] >
             p.elevation_deg[static_cast<std::size_t>(b)];
    });
    dynobj::core::PointCloud by_laser;
    for (int l : ids)
      for (std::size_t i = 0; i < raw.size(); i++)
        if (laser[i] == l) by_laser.push_back(raw.x[i], raw.y[i], raw.z[i], raw.intensity[i]);
    std::string s3, s2;
    const double t3 = medianMs(raw, s3), t2 = medianMs(by_laser, s2);
    std::printf("%-8s %8zu  %7.1f ms (%-16s) %7.1f ms (%s)\n", p.name.c_str(), raw.size(), t3,
                s3.c_str(), t2, s2.c_str());
  }
  return 0;
}
