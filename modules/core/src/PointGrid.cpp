// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/PointGrid.h"

#include <cmath>
#include <limits>

#include "dynobj/core/Config.h"

namespace dynobj::core {

PointGrid::PointGrid(double cell) : cell_(cell) {
  requirePositive("cell", cell_);
}

std::int64_t PointGrid::index(double v) const {
  return static_cast<std::int64_t>(std::floor(v / cell_));
}

std::uint64_t PointGrid::key(std::int64_t i, std::int64_t j) {  // unsigned: no shift of a negative
  return (static_cast<std::uint64_t>(i) << 32) ^ (static_cast<std::uint64_t>(j) & 0xffffffffU);
}

void PointGrid::add(const Eigen::Vector3d& p) {
  cells_[key(index(p.x()), index(p.y()))].push_back(p);
}

double PointGrid::nearestSq(const Eigen::Vector3d& q) const {
  const double reach = cell_ * cell_;
  double best = std::numeric_limits<double>::infinity();
  const std::int64_t ci = index(q.x()), cj = index(q.y());
  for (std::int64_t i = ci - 1; i <= ci + 1; i++)
    for (std::int64_t j = cj - 1; j <= cj + 1; j++) {
      const auto it = cells_.find(key(i, j));
      if (it == cells_.end()) continue;
      for (const Eigen::Vector3d& p : it->second) {
        const double d = (p - q).squaredNorm();
        if (d <= reach && d < best) best = d;
      }
    }
  return best;
}

}  // namespace dynobj::core
