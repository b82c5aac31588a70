// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/MapConsistency.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <random>

namespace dynobj::eval {

namespace {
double ratio(long a, long b) {
  return b > 0 ? static_cast<double>(a) / static_cast<double>(b) : 0;
}
}  // namespace

double ConsistencyReport::flaggedShare() const {
  return ratio(flagged, points);
}
double ConsistencyReport::suspiciousShare() const {
  return ratio(flagged_static, flagged);
}
double ConsistencyReport::transientShare() const {
  return ratio(flagged_transient, flagged);
}

std::string ConsistencyReport::toString() const {
  char b[400];
  std::snprintf(b, sizeof(b),
                "%ld sweeps, %ld points, flagged %.2f %%: on static structure (suspicious) "
                "%.1f %%, transient %.1f %%, undecided %.1f %%; unflagged but transient ~%ld "
                "points (%.2f %% of the sampled)",
                sweeps, points, 100 * flaggedShare(), 100 * suspiciousShare(),
                100 * transientShare(), 100 * ratio(flagged_unknown, flagged), missedEstimate(),
                100 * ratio(unflagged_transient, unflagged_sampled));
  return b;
}

MapConsistency::MapConsistency(const ConsistencyParams& p) : p_(p) {}

void MapConsistency::add(const core::LidarFrame& f, const Eigen::Isometry3d& pose,
                         const cv::Mat_<std::uint8_t>& dynamic) {
  if (!proj_) proj_.emplace(f.sensor);
  Sweep s;
  s.pose = pose;
  s.sensor_from_world = pose.inverse();
  s.range = f.range.clone();
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++) {
      if (!f.valid(r, c)) continue;
      const cv::Vec3f& p = f.xyz(r, c);
      if (std::hypot(p[0], p[1]) > p_.max_range) continue;
      s.points.push_back((pose * Eigen::Vector3d(p[0], p[1], p[2])).cast<float>());
      s.flagged.push_back(dynamic(r, c) ? 1 : 0);
    }
  sweeps_.push_back(std::move(s));
}

MapConsistency::Class MapConsistency::classify(const Eigen::Vector3f& world,
                                               std::size_t own) const {
  const core::SphericalProjection& proj = *proj_;
  const auto n = static_cast<std::size_t>(p_.neighbours);
  int occupied = 0, views = 0;
  for (std::size_t i = own > n ? own - n : 0; i < std::min(sweeps_.size(), own + n + 1); i++) {
    if (i + 1 >= own && i <= own + 1) continue;  // itself and its direct neighbours
    const Eigen::Vector3d q = sweeps_[i].sensor_from_world * world.cast<double>();
    const double d = q.norm();
    int row = -1, col = -1;
    if (d > p_.max_range || d < 1 || !proj.pixelOf(q.x(), q.y(), q.z(), row, col)) continue;
    // A 3x3 window absorbs the pixel grid: occupied if any ray meets the point, free only if
    // every ray with a return passes it.
    const cv::Mat_<float>& R = sweeps_[i].range;
    const double tol = p_.margin + p_.range_factor * d;
    bool hit = false, through = true, any = false;
    for (int dr = -1; dr <= 1; dr++)
      for (int dc = -1; dc <= 1; dc++) {
        const int rr = row + dr, cc = (col + dc + R.cols) % R.cols;
        if (rr < 0 || rr >= R.rows) continue;
        const float seen = R(rr, cc);
        if (seen <= 0) {
          through = false;
          continue;
        }
        any = true;
        if (std::abs(seen - d) <= tol) hit = true;
        if (seen <= d + tol) through = false;
      }
    if (!any) continue;
    if (hit) {
      views++;
      occupied++;
    } else if (through) {
      views++;
    }
  }
  if (views < p_.min_views) return kUnknown;
  if (occupied >= p_.static_share * views) return kStatic;
  if (occupied <= p_.transient_share * views) return kTransient;
  return kBetween;
}

ConsistencyReport MapConsistency::evaluate() {
  ConsistencyReport r;
  r.sweeps = static_cast<long>(sweeps_.size());
  r.unflagged_sample_step = std::max(1, p_.unflagged_sample);
  marks_.clear();
  std::mt19937 rng(1);
  for (std::size_t i = 0; i < sweeps_.size(); i++) {
    const Sweep& s = sweeps_[i];
    for (std::size_t k = 0; k < s.points.size(); k++) {
      r.points++;
      const bool flagged = s.flagged[k] != 0;
      if (!flagged && rng() % static_cast<unsigned>(r.unflagged_sample_step) != 0) continue;
      const Class c = classify(s.points[k], i);
      std::uint8_t colour = 0;
      if (flagged) {
        r.flagged++;
        r.flagged_static += c == kStatic;
        r.flagged_transient += c == kTransient;
        r.flagged_unknown += c == kUnknown;
        colour = c == kStatic ? 3 : c == kTransient ? 2 : 4;
      } else {
        r.unflagged_sampled++;
        r.unflagged_transient += c == kTransient;
        colour = c == kTransient ? 1 : 0;
      }
      marks_.emplace_back(s.points[k], colour);
    }
  }
  return r;
}

cv::Mat MapConsistency::topView(double resolution) const {
  if (sweeps_.empty()) return {};
  Eigen::Vector2d lo(1e18, 1e18), hi(-1e18, -1e18);
  for (const Sweep& s : sweeps_) {
    lo = lo.cwiseMin(s.pose.translation().head<2>());
    hi = hi.cwiseMax(s.pose.translation().head<2>());
  }
  const double pad = std::min(p_.max_range, 40.0);
  lo.array() -= pad;
  hi.array() += pad;
  const int W = static_cast<int>((hi.y() - lo.y()) / resolution) + 1;
  const int H = static_cast<int>((hi.x() - lo.x()) / resolution) + 1;
  cv::Mat img(H, W, CV_8UC3, cv::Scalar(0, 0, 0));
  const auto px = [&](double x, double y) {  // x up, y left
    return cv::Point(static_cast<int>((hi.y() - y) / resolution),
                     static_cast<int>((hi.x() - x) / resolution));
  };
  const cv::Scalar colours[5] = {
      {90, 90, 90}, {0, 200, 0}, {0, 0, 255}, {0, 255, 255}, {255, 0, 255}};
  for (int pass = 0; pass < 2; pass++)  // the static map first, flagged points on top
    for (const auto& [w, c] : marks_) {
      if ((c >= 2) != (pass == 1)) continue;
      const cv::Point q = px(w.x(), w.y());
      if (q.x >= 0 && q.y >= 0 && q.x < W && q.y < H) cv::circle(img, q, 1, colours[c], -1);
    }
  for (const Sweep& s : sweeps_)
    cv::circle(img, px(s.pose.translation().x(), s.pose.translation().y()), 2, {255, 200, 0}, -1);
  return img;
}

}  // namespace dynobj::eval
