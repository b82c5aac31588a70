// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/GroundLeveler.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <vector>

namespace dynobj::mapclean {
namespace {

/// Least-squares plane of `pts` (normal up); empty with fewer than 3 points.
std::optional<GroundPlane> planeOf(const std::vector<Eigen::Vector3d>& pts) {
  if (pts.size() < 3) return std::nullopt;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : pts) mean += p;
  mean /= static_cast<double>(pts.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) cov += (p - mean) * (p - mean).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
  GroundPlane g;
  g.normal = es.eigenvectors().col(0);  // smallest eigenvalue
  if (g.normal.z() < 0) g.normal = -g.normal;
  g.distance = g.normal.dot(mean) * -1.0;
  g.inliers = pts.size();
  return g;
}

}  // namespace

GroundLeveler::GroundLeveler(double max_range, std::size_t min_points)
    : max_range_(max_range), min_points_(min_points) {}

std::optional<GroundPlane> GroundLeveler::fit(const core::LidarFrame& frame) {
  segmenter_.segment(frame, ground_);
  std::vector<Eigen::Vector3d> pts;
  for (int r = 0; r < frame.rows(); r++)
    for (int c = 0; c < frame.cols(); c++)
      if (ground_(r, c) && frame.isValid(r, c) && frame.range(r, c) <= max_range_) {
        const cv::Vec3f& p = frame.xyz(r, c);
        pts.emplace_back(p[0], p[1], p[2]);
      }
  auto g = planeOf(pts);
  if (!g) return std::nullopt;
  std::vector<Eigen::Vector3d> in;  // one refit without the returns off the plane (curbs, feet)
  for (const auto& p : pts)
    if (std::abs(g->normal.dot(p) + g->distance) < 0.05) in.push_back(p);
  g = planeOf(in);
  if (!g || g->inliers < min_points_ || g->normal.z() < 0.9)
    return std::nullopt;  // > 25 deg: not a floor
  return g;
}

Eigen::Isometry3d GroundLeveler::level(const Eigen::Isometry3d& pose, const GroundPlane& plane) {
  // Tilt: the smallest rotation taking the plane normal (sensor frame) to the world's up.
  const Eigen::Matrix3d tilt =
      Eigen::Quaterniond::FromTwoVectors(plane.normal, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d fwd = pose.linear().col(0), fwd_tilt = tilt.col(0);
  const double yaw = std::atan2(fwd.y(), fwd.x()) - std::atan2(fwd_tilt.y(), fwd_tilt.x());
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  out.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * tilt;
  if (!floor_z_) floor_z_ = pose.translation().z() - plane.distance;
  out.translation() =
      Eigen::Vector3d(pose.translation().x(), pose.translation().y(), *floor_z_ + plane.distance);
  return out;
}

}  // namespace dynobj::mapclean
