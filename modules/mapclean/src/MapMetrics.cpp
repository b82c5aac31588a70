// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapMetrics.h"

#include <cmath>
#include <nanoflann.hpp>
#include <stdexcept>
#include <string>

namespace dynobj::mapclean {
namespace {

struct Adaptor {
  const std::vector<MapPoint>& pts;
  std::size_t kdtree_get_point_count() const { return pts.size(); }
  float kdtree_get_pt(std::size_t i, std::size_t d) const {
    return d == 0 ? pts[i].x : d == 1 ? pts[i].y : pts[i].z;
  }
  template <class BBOX>
  bool kdtree_get_bbox(BBOX& /*bb*/) const {
    return false;
  }
};

using Tree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, Adaptor>, Adaptor, 3>;

std::optional<double> ratio(std::size_t num, std::size_t den) {
  if (den == 0) return std::nullopt;
  return static_cast<double>(num) / static_cast<double>(den);
}

}  // namespace

struct MapEvaluator::Index {
  Adaptor adaptor;
  Tree tree;
  explicit Index(const std::vector<MapPoint>& p)
      : adaptor{p}, tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)) {
    tree.buildIndex();
  }
};

std::optional<double> MapScores::sa() const {
  return ratio(static_kept, gt_static);
}
std::optional<double> MapScores::da() const {
  return ratio(dynamic_removed, gt_dynamic);
}
std::optional<double> MapScores::aa() const {
  const auto a = sa(), d = da();
  if (!a || !d) return std::nullopt;
  return std::sqrt(*a * *d);
}

MapEvaluator::MapEvaluator(std::vector<MapPoint> static_map, double tolerance)
    : map_(std::move(static_map)), tol2_(tolerance * tolerance), hits_(map_.size(), 0) {
  if (!(tolerance > 0))
    throw std::invalid_argument("tolerance must be > 0, got " + std::to_string(tolerance));
  if (!map_.empty()) index_ = std::make_unique<Index>(map_);
  s_.map_points = map_.size();
}

MapEvaluator::~MapEvaluator() = default;

void MapEvaluator::add(float x, float y, float z, bool dynamic) {
  (dynamic ? s_.gt_dynamic : s_.gt_static)++;
  bool near = false;
  if (index_) {
    const float q[3] = {x, y, z};
    std::size_t idx = 0;
    float d2 = 0;
    nanoflann::KNNResultSet<float> rs(1);
    rs.init(&idx, &d2);
    index_->tree.findNeighbors(rs, q, nanoflann::SearchParams());
    if (rs.size() == 1 && d2 <= tol2_) {
      near = true;
      hits_[idx] |= dynamic ? 2 : 1;
    }
  }
  if (dynamic && !near) s_.dynamic_removed++;
  if (!dynamic && near) s_.static_kept++;
}

MapScores MapEvaluator::scores() const {
  MapScores s = s_;
  s.ghost_points = 0;
  for (auto h : hits_)
    if (h == 2) s.ghost_points++;
  return s;
}

}  // namespace dynobj::mapclean
