// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/MotionFromMatches.h"

#include <algorithm>
#include <cmath>

#include "dynobj/core/Se3.h"

namespace dynobj::core {
namespace {

/// Closed-form rigid transform (Umeyama, no scale) mapping src[i] onto dst[i].
Eigen::Isometry3d rigidFit(const std::vector<Eigen::Vector3d>& src,
                           const std::vector<Eigen::Vector3d>& dst) {
  Eigen::Matrix3Xd a(3, static_cast<Eigen::Index>(src.size())), b(3, a.cols());
  for (Eigen::Index i = 0; i < a.cols(); i++) {
    a.col(i) = src[static_cast<std::size_t>(i)];
    b.col(i) = dst[static_cast<std::size_t>(i)];
  }
  Eigen::Isometry3d T;
  T.matrix() = Eigen::umeyama(a, b, false);
  return T;
}

/// T minimising sum_i e_i^T W_i e_i, e_i = T src_i - dst_i: Gauss-Newton on SE(3) from `T`.
Eigen::Isometry3d weightedFit(const std::vector<Eigen::Vector3d>& src,
                              const std::vector<Eigen::Vector3d>& dst,
                              const std::vector<Eigen::Matrix3d>& W, Eigen::Isometry3d T) {
  constexpr int kSteps = 5;
  for (int it = 0; it < kSteps; it++) {
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    for (std::size_t i = 0; i < src.size(); i++) {
      const Eigen::Vector3d q = T * src[i];
      Eigen::Matrix<double, 3, 6> J;  // d(residual) / d(omega, v), left increment
      J.leftCols<3>() << 0, q.z(), -q.y(), -q.z(), 0, q.x(), q.y(), -q.x(), 0;
      J.rightCols<3>().setIdentity();
      const Eigen::Matrix<double, 6, 3> JtW = J.transpose() * W[i];
      H.noalias() += JtW * J;
      g.noalias() += JtW * (q - dst[i]);
    }
    const Eigen::Matrix<double, 6, 1> xi = H.ldlt().solve(-g);
    if (!xi.allFinite()) break;
    T = expSE3(xi) * T;
    if (xi.head<3>().norm() < 1e-7 && xi.tail<3>().norm() < 1e-6) break;
  }
  return T;
}

}  // namespace

EgoMotion motionFromMatches(const std::vector<PointMatch>& matches, const EgoMotionParams& p,
                            const PixelPitch& pitch, std::mt19937& rng) {
  EgoMotion em;
  em.matches = static_cast<int>(matches.size());
  if (em.matches < std::max(3, p.min_inliers)) return em;
  const auto n = matches.size();
  auto threshold = [&](const PointMatch& m) {  // [m] isotropic inlier distance
    return p.inlier_distance + p.inlier_range_factor * m.cur.norm();
  };
  // pixel_spread: each residual weighed by the inverse of its threshold squared plus its spread.
  const bool spread = p.pixel_spread > 0;
  std::vector<Eigen::Matrix3d> info;
  if (spread) {
    info.resize(n);
    for (std::size_t i = 0; i < n; i++) {
      const double thr = threshold(matches[i]);
      info[i] = (thr * thr * Eigen::Matrix3d::Identity() +
                 p.pixel_spread * p.pixel_spread * matches[i].spread)
                    .inverse();
    }
  }
  // still_match_pixels: does T move a still match's point more than that across or along the scan?
  const bool check_still = p.still_match_pixels > 0 && pitch.row > 0;
  auto movesAway = [&](const Eigen::Vector3d& s, const Eigen::Vector3d& q) {
    const double du = std::remainder(std::atan2(q.y(), q.x()) - std::atan2(s.y(), s.x()), 2 * M_PI);
    const double dv = std::atan2(q.z(), q.head<2>().norm()) - std::atan2(s.z(), s.head<2>().norm());
    return std::abs(du) > p.still_match_pixels * pitch.column ||
           std::abs(dv) > p.still_match_pixels * pitch.row;
  };
  auto countInliers = [&](const Eigen::Isometry3d& T, std::vector<char>& flags) {
    int k = 0;
    for (std::size_t i = 0; i < n; i++) {
      const PointMatch& m = matches[i];
      const Eigen::Vector3d q = T * m.cur;
      const Eigen::Vector3d e = q - m.prev;
      if (check_still && m.still && movesAway(m.cur, q))
        flags[i] = 0;
      else if (spread)
        flags[i] = e.dot(info[i] * e) < 1.0;
      else
        flags[i] = e.norm() < threshold(m);
      k += flags[i];
    }
    return k;
  };

  // RANSAC over minimal 3-point samples.
  std::uniform_int_distribution<int> pick(0, em.matches - 1);
  std::vector<char> best_in, in(n);
  int best = 0;
  std::vector<Eigen::Vector3d> s3(3), d3(3);
  int needed = p.iterations;  // shrinks as the best inlier ratio w grows (adaptive RANSAC)
  for (int it = 0; it < needed; it++) {
    const auto i0 = static_cast<std::size_t>(pick(rng)), i1 = static_cast<std::size_t>(pick(rng)),
               i2 = static_cast<std::size_t>(pick(rng));
    if (i0 == i1 || i1 == i2 || i0 == i2) continue;
    s3 = {matches[i0].cur, matches[i1].cur, matches[i2].cur};
    d3 = {matches[i0].prev, matches[i1].prev, matches[i2].prev};
    if ((s3[1] - s3[0]).cross(s3[2] - s3[0]).norm() < 1e-3) continue;  // degenerate sample
    const int k = countInliers(rigidFit(s3, d3), in);
    if (k > best) {
      best = k;
      best_in = in;
      const double w3 = std::pow(static_cast<double>(k) / em.matches, 3);  // P(all inliers)
      if (p.confidence < 1 && w3 > 0 && w3 < 1)
        needed = std::min(
            needed, static_cast<int>(std::ceil(std::log(1 - p.confidence) / std::log(1 - w3))));
    }
  }
  if (best < 3) return em;
  // Least squares on the inliers, re-selecting them with the refined motion until they settle
  // (at most `refinements` times): a sample's inlier set is only as good as its 3 points.
  std::vector<Eigen::Vector3d> si, di;
  std::vector<Eigen::Matrix3d> wi;
  for (int pass = 0; pass <= p.refinements; pass++) {
    si.clear();
    di.clear();
    wi.clear();
    for (std::size_t i = 0; i < n; i++)
      if (best_in[i]) {
        si.push_back(matches[i].cur);
        di.push_back(matches[i].prev);
        if (spread) wi.push_back(info[i]);
      }
    em.motion = rigidFit(si, di);
    if (spread) em.motion = weightedFit(si, di, wi, em.motion);
    em.inliers = countInliers(em.motion, in);
    if (in == best_in) break;
    best_in = in;
  }
  em.ok = em.inliers >= p.min_inliers && em.inliers >= p.min_inlier_ratio * em.matches;
  em.source = "intensity";
  return em;
}

}  // namespace dynobj::core
