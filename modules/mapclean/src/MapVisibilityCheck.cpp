// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapVisibilityCheck.h"

#include <dynobj/core/SphericalProjection.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynobj::mapclean {
namespace {

constexpr float kNone = std::numeric_limits<float>::infinity();

/// Per pixel: the nearest valid return in its (2w+1)^2 window (columns wrap around: azimuth is
/// circular; rows do not). +inf where the window holds no return.
void nearestInWindow(const core::LidarFrame& f, int w, cv::Mat_<float>& out) {
  const int rows = f.rows(), cols = f.cols();
  cv::Mat_<float> row_min(rows, cols);
  for (int r = 0; r < rows; r++)
    for (int c = 0; c < cols; c++) {
      float m = kNone;
      for (int d = -w; d <= w; d++) {
        const int cc = ((c + d) % cols + cols) % cols;
        if (f.isValid(r, cc)) m = std::min(m, f.range(r, cc));
      }
      row_min(r, c) = m;
    }
  out.create(rows, cols);
  for (int r = 0; r < rows; r++)
    for (int c = 0; c < cols; c++) {
      float m = kNone;
      for (int rr = std::max(0, r - w); rr <= std::min(rows - 1, r + w); rr++)
        m = std::min(m, row_min(rr, c));
      out(r, c) = m;
    }
}

void bump(std::uint16_t& n) {
  if (n < std::numeric_limits<std::uint16_t>::max()) n++;
}

}  // namespace

MapVisibilityCheck::MapVisibilityCheck(const VisibilityParams& p, std::vector<VoxelCentre> voxels)
    : p_(p), voxels_(std::move(voxels)), free_(voxels_.size(), 0), hit_(voxels_.size(), 0) {}

MapVisibilityCheck::~MapVisibilityCheck() = default;

void MapVisibilityCheck::addScan(const core::LidarFrame& frame,
                                 const Eigen::Isometry3d& sensor_pose) {
  const core::SensorModel& s = frame.sensor;
  if (!projection_ || projection_->sensor().rows != s.rows || projection_->sensor().cols != s.cols)
    projection_ = std::make_unique<core::SphericalProjection>(s);
  nearestInWindow(frame, std::max(0, p_.window), nearest_);
  scans_++;
  const Eigen::Isometry3f to_sensor = sensor_pose.inverse().cast<float>();
  const float near = static_cast<float>(std::max(p_.min_range, s.min_range));
  const float far = static_cast<float>(s.max_range);
  const auto margin = static_cast<float>(p_.margin), margin_rel = static_cast<float>(p_.margin_rel);
  for (std::size_t i = 0; i < voxels_.size(); i++) {
    const VoxelCentre& v = voxels_[i];
    const Eigen::Vector3f q = to_sensor * Eigen::Vector3f(v.x, v.y, v.z);
    const float range = q.norm();
    if (range < near || range > far) continue;
    int r = -1, c = -1;
    if (!projection_->pixelOf(q.x(), q.y(), q.z(), r, c) || !frame.isValid(r, c)) continue;
    const float tol = margin + margin_rel * range;
    if (nearest_(r, c) > range + tol)
      bump(free_[i]);  // every beam around it ends beyond it
    else if (std::abs(frame.range(r, c) - range) <= tol)
      bump(hit_[i]);
  }
}

std::vector<std::uint64_t> MapVisibilityCheck::seenThrough() const {
  std::vector<std::uint64_t> keys;
  for (std::size_t i = 0; i < voxels_.size(); i++)
    if (free_[i] >= p_.min_views && free_[i] >= p_.ratio * hit_[i]) keys.push_back(voxels_[i].key);
  std::sort(keys.begin(), keys.end());
  return keys;
}

}  // namespace dynobj::mapclean
