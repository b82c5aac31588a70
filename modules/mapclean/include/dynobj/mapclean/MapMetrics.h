// SPDX-License-Identifier: BSD-3-Clause
// Map-level metrics of the KTH DynamicMap benchmark (Zhang et al., ITSC 2023): every ground-truth
// point (all points of all scans, in the world, labelled static or dynamic) is "kept" when the
// cleaned static map has a point within `tolerance` of it, else "removed".
//   SA = kept static / all static,  DA = removed dynamic / all dynamic,  AA = sqrt(SA * DA).
// Ghost points: static-map points that only dynamic ground truth explains (some dynamic
// ground-truth point chose it as its nearest map point within the tolerance, no static one did).
// Ground truth streams in one point at a time (memory: the static map only).
#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {

struct MapScores {
  std::size_t gt_static = 0, gt_dynamic = 0;
  std::size_t static_kept = 0, dynamic_removed = 0;
  std::size_t map_points = 0, ghost_points = 0;
  std::optional<double> sa() const;  ///< [0, 1]; empty without static ground truth
  std::optional<double> da() const;  ///< [0, 1]; empty without dynamic ground truth
  std::optional<double> aa() const;  ///< sqrt(SA * DA); empty unless both are defined
};

class MapEvaluator {
 public:
  /// `static_map`: the cleaned map; `tolerance` [m] > 0 (the benchmark uses 0.05 m).
  MapEvaluator(std::vector<MapPoint> static_map, double tolerance);
  ~MapEvaluator();
  MapEvaluator(const MapEvaluator&) = delete;
  MapEvaluator& operator=(const MapEvaluator&) = delete;

  /// One ground-truth point (world frame) and its label.
  void add(float x, float y, float z, bool dynamic);
  MapScores scores() const;

 private:
  struct Index;
  std::vector<MapPoint> map_;
  double tol2_;
  std::unique_ptr<Index> index_;
  std::vector<std::uint8_t> hits_;  ///< per map point: bit 0 = a static GT point, bit 1 = dynamic
  MapScores s_;
};

}  // namespace dynobj::mapclean
