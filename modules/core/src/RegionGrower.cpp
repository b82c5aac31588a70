// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/RegionGrower.h"

#include <cmath>
#include <memory>

#include "dynobj/core/Config.h"
#include "dynobj/core/PointGrid.h"

namespace dynobj::core {

void RegionGrowingParams::visit(ParamVisitor& v) {
  v.value("distance", distance, kPositive);
  v.value("range_factor", range_factor, {0, 100});
  v.value("depth_factor", depth_factor, {0, 1});
  v.value("slope_factor", slope_factor, {0, 100});
  v.value("set_back_radius", set_back_radius, {0, 100});
  v.value("max_extent", max_extent, kPositive);
  v.value("max_pixels", max_pixels, {1, 10000000});
  v.value("keep_out_settled", keep_out_settled);
  v.value("nearer_rest_radius", nearer_rest_radius, {0, 10});
  v.value("past_surface_check", past_surface_check);
}

bool RegionGrowingParams::joins(const cv::Vec3f& p, double rp, const cv::Vec3f& q, double rq,
                                double gap, bool q_above) const {
  const cv::Vec3f d = q - p;
  const double d2 = static_cast<double>(d.dot(d)), step = std::abs(rq - rp);
  const double eps = distance + range_factor * rp * gap;
  const double depth = distance + depth_factor * rp;
  if (d2 <= eps * eps && step <= depth) return true;
  if (!q_above || rq <= rp) return false;
  // A top set back from the face below it, where the rows are too far apart for the test above.
  // Across the rays, |p - q|^2 - (rq - rp)^2 = 2 rp rq (1 - cos angle): the distance with the
  // step along them taken out.
  const double set_back = slope_factor * rp * gap;
  return set_back > depth && step <= set_back && d2 - step * step <= eps * eps;
}

RegionGrower::RegionGrower(const RegionGrowingParams& p) : p_(p) {
  p_.validate();
}

RegionGrower::Admit RegionGrower::nearerOwnSeeds(const LidarFrame& frame,
                                                 const std::vector<std::vector<int>>& seeds,
                                                 const std::vector<std::vector<int>>& others,
                                                 double radius, Admit then) {
  auto grid = [&frame, radius](const std::vector<int>& pixels) {
    PointGrid g(radius);
    for (int px : pixels) {
      const cv::Vec3f& p = frame.pointAt(px);
      g.add(Eigen::Vector3d(p[0], p[1], p[2]));
    }
    return g;
  };
  // Grids only for the objects that have others beside them (the rest stay empty, unread).
  auto own = std::make_shared<std::vector<PointGrid>>(seeds.size(), PointGrid(radius));
  auto rest = std::make_shared<std::vector<PointGrid>>(seeds.size(), PointGrid(radius));
  bool any = false;
  for (std::size_t i = 0; i < seeds.size() && i < others.size(); i++) {
    if (others[i].empty()) continue;
    (*own)[i] = grid(seeds[i]);
    (*rest)[i] = grid(others[i]);
    any = true;
  }
  if (!any) return then;
  return [&frame, own, rest, then = std::move(then)](std::size_t obj, int px) {
    if (then && !then(obj, px)) return false;
    const PointGrid& r = (*rest)[obj];
    if (r.empty()) return true;
    const cv::Vec3f& p = frame.pointAt(px);
    const Eigen::Vector3d q(p[0], p[1], p[2]);
    const double to_rest = r.nearestSq(q);
    return !std::isfinite(to_rest) || (*own)[obj].nearestSq(q) <= to_rest;
  };
}

void RegionGrower::keepOut(const std::vector<int>& pixels, cv::Mat_<int>& owner) {
  int* own = owner.ptr<int>(0);
  for (int px : pixels)
    if (own[px] == kFree) own[px] = kKeptOut;
}

std::vector<int> RegionGrower::grow(const LidarFrame& f, const cv::Mat_<std::uint8_t>& ground,
                                    const std::vector<std::vector<int>>& seeds,
                                    cv::Mat_<std::uint8_t>& mask, cv::Mat_<int>& owner,
                                    const Admit& admit) {
  const int H = f.rows(), W = f.cols();
  if (mask.size() != f.range.size()) mask = cv::Mat_<std::uint8_t>(H, W, std::uint8_t{0});
  if (owner.size() != f.range.size()) owner = cv::Mat_<int>(H, W, kFree);
  // Angular gaps between neighbouring pixels: how far apart two points of one surface can be,
  // vertically (between beams) and horizontally (between columns).
  const double gap_v = f.sensor.fovSpan() / H, gap_h = 2 * M_PI / W;
  std::vector<int> counts(seeds.size(), 0);
  refused_.clear();
  for (std::size_t obj = 0; obj < seeds.size(); obj++) {
    if (seeds[obj].empty()) continue;
    double cx = 0, cy = 0;
    for (int px : seeds[obj]) {
      cx += f.pointAt(px)[0];
      cy += f.pointAt(px)[1];
    }
    cx /= static_cast<double>(seeds[obj].size());
    cy /= static_cast<double>(seeds[obj].size());
    double seed_radius = 0;  // large objects (cars) may grow farther than small ones
    for (int px : seeds[obj])
      seed_radius = std::max(seed_radius, std::hypot(f.pointAt(px)[0] - cx, f.pointAt(px)[1] - cy));
    const double extent = std::max(p_.max_extent, seed_radius + p_.max_extent / 2);
    const bool wide = seed_radius > p_.set_back_radius;  // wider than a person: a top set back
    queue_.clear();
    for (int px : seeds[obj]) {
      const int r = px / W, c = px % W;
      if (!f.isValid(r, c) || owner(r, c) != kFree) continue;
      owner(r, c) = static_cast<int>(obj);
      mask(r, c) = 255;
      queue_.push_back(px);
    }
    for (std::size_t head = 0;
         head < queue_.size() && static_cast<int>(queue_.size()) < p_.max_pixels; head++) {
      const int r = queue_[head] / W, c = queue_[head] % W;
      const cv::Vec3f& p = f.xyz(r, c);
      const double rng = f.range(r, c);
      for (int dr = -1; dr <= 1; dr++) {
        const int rr = r + dr;
        if (rr < 0 || rr >= H) continue;
        for (int dc = -1; dc <= 1; dc++) {  // N8 of Eq. (24)
          if (dr == 0 && dc == 0) continue;
          const int cc = (c + dc + W) % W;
          if (!f.isValid(rr, cc) || owner(rr, cc) != kFree || ground(rr, cc)) continue;
          const cv::Vec3f& q = f.xyz(rr, cc);
          const double gap = dr == 0 ? gap_h : (dc == 0 ? gap_v : std::hypot(gap_h, gap_v));
          if (!p_.joins(p, rng, q, f.range(rr, cc), gap, wide && dr == -1 && dc == 0)) continue;
          if (std::hypot(q[0] - cx, q[1] - cy) > extent) continue;
          if (admit && !admit(obj, rr * W + cc)) {
            owner(rr, cc) = kKeptOut;
            refused_.push_back(rr * W + cc);
            continue;
          }
          owner(rr, cc) = static_cast<int>(obj);
          mask(rr, cc) = 255;
          queue_.push_back(rr * W + cc);
        }
      }
    }
    counts[obj] = static_cast<int>(queue_.size());
  }
  return counts;
}

}  // namespace dynobj::core
