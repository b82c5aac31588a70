// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapVisibilityCheck.h"

#include <dynobj/core/SphericalProjection.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <vector>

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
    : p_(p), voxels_(std::move(voxels)), views_(voxels_.size()) {}

MapVisibilityCheck::MapVisibilityCheck(const VisibilityParams& p) : p_(p) {}

MapVisibilityCheck::~MapVisibilityCheck() = default;

MapVisibilityCheck::ScanView MapVisibilityCheck::prepare(const core::LidarFrame& frame,
                                                         const Eigen::Isometry3d& sensor_pose) {
  const core::SensorModel& s = frame.sensor;
  if (!projection_ || projection_->sensor().rows != s.rows || projection_->sensor().cols != s.cols)
    projection_ = std::make_unique<core::SphericalProjection>(s);
  scans_++;
  ScanView v;
  v.timestamp_ns = frame.timestamp_ns;
  cv::Mat_<float> range(frame.rows(), frame.cols(), 0.f);
  frame.range.copyTo(range, frame.valid);
  cv::Mat_<float> nearest;
  nearestInWindow(frame, std::max(0, p_.window), nearest);
  cv::merge(std::vector<cv::Mat>{range, nearest}, v.images);
  v.to_sensor = sensor_pose.inverse().cast<float>();
  v.near = static_cast<float>(std::max(p_.min_range, s.min_range));
  v.far = static_cast<float>(s.max_range);
  return v;
}

template <class T>
void MapVisibilityCheck::count(const ScanView& scan, float x, float y, float z,
                               VoxelMap::Views& views) const {
  const Eigen::Vector3f q = scan.to_sensor * Eigen::Vector3f(x, y, z);
  const float range = q.norm();
  if (range < scan.near || range > scan.far) return;
  int r = -1, c = -1;
  if (!projection_->pixelOf(q.x(), q.y(), q.z(), r, c)) return;
  const auto& px = scan.images.at<cv::Vec<T, 2>>(r, c);
  const auto measured = static_cast<float>(px[0]);
  if (!(measured > 0.f)) return;  // no return there
  const float tol = static_cast<float>(p_.margin) + static_cast<float>(p_.margin_rel) * range;
  if (static_cast<float>(px[1]) > range + tol)
    bump(views.free);  // every beam around it ends beyond it
  else if (std::abs(measured - range) <= tol)
    bump(views.hit);
}

void MapVisibilityCheck::addScan(const core::LidarFrame& frame,
                                 const Eigen::Isometry3d& sensor_pose) {
  const ScanView scan = prepare(frame, sensor_pose);
  for (std::size_t i = 0; i < voxels_.size(); i++)
    count<float>(scan, voxels_[i].x, voxels_[i].y, voxels_[i].z, views_[i]);
}

void MapVisibilityCheck::addScan(const core::LidarFrame& frame,
                                 const Eigen::Isometry3d& sensor_pose, VoxelMap& map) {
  ScanView scan = prepare(frame, sensor_pose);
  map.forEachVoxel(
      [&](float x, float y, float z, VoxelMap::Views& v) { count<float>(scan, x, y, z, v); });
  if (p_.past <= 0) return;
  scan.images.convertTo(scan.images, CV_16F);
  past_.push_back(std::move(scan));
}

void MapVisibilityCheck::countPast(VoxelMap& map, const std::vector<std::uint64_t>& keys,
                                   std::int64_t now_ns) {
  const auto past_ns = static_cast<std::int64_t>(p_.past * 1e9);
  while (!past_.empty() && (now_ns - past_.front().timestamp_ns > past_ns ||
                            now_ns < past_.front().timestamp_ns))  // or the clock went back
    past_.pop_front();
  if (past_.empty() || keys.empty()) return;
  map.forVoxels(keys, [&](float x, float y, float z, VoxelMap::Views& v) {
    for (const ScanView& scan : past_) count<cv::float16_t>(scan, x, y, z, v);
  });
}

std::vector<std::uint64_t> MapVisibilityCheck::seenThrough() const {
  std::vector<std::uint64_t> keys;
  for (std::size_t i = 0; i < voxels_.size(); i++)
    if (isSeenThrough(views_[i])) keys.push_back(voxels_[i].key);
  std::sort(keys.begin(), keys.end());
  return keys;
}

}  // namespace dynobj::mapclean
