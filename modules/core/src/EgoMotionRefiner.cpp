// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/EgoMotionRefiner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "dynobj/core/Config.h"

namespace dynobj::core {

void EgoRefinementParams::visit(ParamVisitor& v) {
  v.value("enabled", enabled);
  v.value("points", points);
  v.value("iterations", iterations);
  v.value("coarse_iterations", coarse_iterations);
  v.value("max_distance", max_distance);
  v.value("final_distance", final_distance);
  v.value("huber", huber);
  v.value("damping", damping);
  v.value("min_correspondences", min_correspondences);
  v.value("max_correction", max_correction);
  v.degrees("max_correction_angle", max_correction_angle);
}

void EgoRefinementParams::validate() const {
  requireInRange("points", points, 10, 10000000);
  requireInRange("iterations", iterations, 1, 100);
  requireInRange("coarse_iterations", coarse_iterations, 0, 100);
  requirePositive("max_distance", max_distance);
  requirePositive("final_distance", final_distance);
  if (final_distance > max_distance)
    throwParameterError("final_distance", "must not exceed max_distance");
  requirePositive("huber", huber);
  requireInRange("damping", damping, 0, 1e6);
  requireInRange("min_correspondences", min_correspondences, 6, 10000000);
  requirePositive("max_correction", max_correction);
  requirePositive("max_correction_angle", max_correction_angle);
}

namespace {

constexpr std::size_t kCoarseStride = 4;  ///< coarse steps use every 4th sampled point

/// Normal of the range image at (r, c) from its four neighbours (columns wrap), or (0,0,0) when a
/// neighbour is missing (range 0) or lies on another surface (range jump).
cv::Vec3f normalAt(const cv::Mat_<float>& range, const cv::Mat_<cv::Vec3f>& xyz, int r, int c) {
  const int rows = range.rows, cols = range.cols;
  const float here = range(r, c);
  if (r == 0 || r == rows - 1 || here <= 0) return {0, 0, 0};
  const int cl = (c + cols - 1) % cols, cr = (c + 1) % cols;
  const float jump = 0.1f * here + 0.1f;
  for (const float n : {range(r, cl), range(r, cr), range(r - 1, c), range(r + 1, c)})
    if (n <= 0 || std::abs(n - here) > jump) return {0, 0, 0};
  const cv::Vec3f n = (xyz(r, cr) - xyz(r, cl)).cross(xyz(r + 1, c) - xyz(r - 1, c));
  const float len = static_cast<float>(cv::norm(n));
  return len > 1e-9f ? n / len : cv::Vec3f(0, 0, 0);
}

Eigen::Isometry3d expSE3(const Eigen::Matrix<double, 6, 1>& xi) {  // (omega, v), left increment
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d w = xi.head<3>();
  const double a = w.norm();
  if (a > 1e-12) T.linear() = Eigen::AngleAxisd(a, w / a).toRotationMatrix();
  T.translation() = xi.tail<3>();
  return T;
}

}  // namespace

EgoMotionRefiner::EgoMotionRefiner(const EgoRefinementParams& p) : p_(p) {
  p_.validate();
}

void EgoMotionRefiner::remember(const LidarFrame& f) {
  if (!p_.enabled) return;
  if (!proj_ || proj_->sensor().rows != f.rows() || proj_->sensor().cols != f.cols())
    proj_.emplace(f.sensor);
  f.range.copyTo(prev_range_);
  f.xyz.copyTo(prev_xyz_);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  prev_normal_.create(f.rows(), f.cols());
  prev_normal_.setTo(cv::Vec3f(nan, nan, nan));
  have_prev_ = true;
}

EgoRefinement EgoMotionRefiner::refine(const LidarFrame& f, const Eigen::Isometry3d& init,
                                       const cv::Mat_<std::uint8_t>& exclude_prev) const {
  EgoRefinement out;
  out.motion = init;
  if (!p_.enabled || !have_prev_ || prev_xyz_.size() != f.xyz.size()) return out;
  const bool use_exclude = exclude_prev.size() == f.xyz.size();

  // Evenly spaced valid pixels of the current frame.
  std::vector<Eigen::Vector3d> pts;
  const int n_valid = cv::countNonZero(f.valid);
  const int step = std::max(1, n_valid / p_.points);
  pts.reserve(static_cast<std::size_t>(n_valid / step + 1));
  int k = 0;
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++)
      if (f.isValid(r, c) && k++ % step == 0) {
        const cv::Vec3f& p = f.xyz(r, c);
        pts.emplace_back(p[0], p[1], p[2]);
      }

  Eigen::Isometry3d T = init;
  const int iters = p_.iterations;
  for (int it = 0; it < iters; it++) {
    const double gate =
        iters == 1 ? p_.max_distance
                   : p_.max_distance + (p_.final_distance - p_.max_distance) * it / (iters - 1);
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    int n = 0;
    // Coarse to fine: the first steps, which only bring the estimate near, use a quarter of the
    // points (and need a quarter of the partners); the last ones, which set it, use them all.
    const std::size_t stride = it < p_.coarse_iterations ? kCoarseStride : 1;
    const int needed = p_.min_correspondences / static_cast<int>(stride);
    for (std::size_t i = 0; i < pts.size(); i += stride) {
      const Eigen::Vector3d& p = pts[i];
      const Eigen::Vector3d q = T * p;  // into the previous frame
      int r, c;
      if (!proj_->pixelOf(q.x(), q.y(), q.z(), r, c)) continue;
      if (use_exclude && exclude_prev(r, c)) continue;
      cv::Vec3f& nv = prev_normal_(r, c);
      if (std::isnan(nv[0])) nv = normalAt(prev_range_, prev_xyz_, r, c);
      if (nv[0] == 0 && nv[1] == 0 && nv[2] == 0) continue;
      const cv::Vec3f& sv = prev_xyz_(r, c);
      const Eigen::Vector3d s(sv[0], sv[1], sv[2]), nn(nv[0], nv[1], nv[2]);
      const Eigen::Vector3d d = q - s;
      if (d.squaredNorm() > gate * gate) continue;
      const double e = nn.dot(d);
      const double w = std::abs(e) <= p_.huber ? 1.0 : p_.huber / std::abs(e);
      Eigen::Matrix<double, 6, 1> J;
      J.head<3>() = q.cross(nn);
      J.tail<3>() = nn;
      H.noalias() += w * J * J.transpose();
      g.noalias() += w * e * J;
      n++;
    }
    out.correspondences = n;
    if (n < needed) return out;  // keep init, ok = false
    const double lambda = p_.damping * H.trace() / 6.0;
    H.diagonal().array() += lambda;
    const Eigen::Matrix<double, 6, 1> xi = H.ldlt().solve(-g);
    T = expSE3(xi) * T;
    if (stride == 1 && xi.head<3>().norm() < 1e-6 && xi.tail<3>().norm() < 1e-5) break;
  }
  const Eigen::Isometry3d change = init.inverse() * T;
  if (change.translation().norm() > p_.max_correction ||
      Eigen::AngleAxisd(change.linear()).angle() > p_.max_correction_angle)
    return out;
  out.motion = T;
  out.motion.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  out.ok = true;
  return out;
}

}  // namespace dynobj::core
