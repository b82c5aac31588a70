// SPDX-License-Identifier: BSD-3-Clause
// A uniform grid of points, hashed by their horizontal cell: the nearest point within one cell
// size of a query, exactly (3 x 3 cells searched). For the few hundred points of one object or
// two, where a k-d tree's build costs more than it saves.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace dynobj::core {

class PointGrid {
 public:
  /// `cell` [m]: the grid's cell size, and the radius nearestSq() answers within.
  explicit PointGrid(double cell);

  void add(const Eigen::Vector3d& p);
  bool empty() const { return cells_.empty(); }
  double cell() const { return cell_; }

  /// Squared distance from `q` to the nearest point within cell() of it; +infinity when none is.
  double nearestSq(const Eigen::Vector3d& q) const;

 private:
  std::int64_t index(double v) const;
  static std::uint64_t key(std::int64_t i, std::int64_t j);
  double cell_;
  std::unordered_map<std::uint64_t, std::vector<Eigen::Vector3d>> cells_;
};

}  // namespace dynobj::core
