// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/VoxelMap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynobj::mapclean {
namespace {

constexpr std::int64_t kHalfRange = std::int64_t{1} << 20;  // 21 bits per axis, signed

std::uint64_t packAxis(double v, double voxel) {
  const auto i = static_cast<std::int64_t>(std::floor(v / voxel));
  if (i < -kHalfRange || i >= kHalfRange)
    throw std::out_of_range("point coordinate " + std::to_string(v) +
                            " m is too far from the origin for the voxel map");
  return static_cast<std::uint64_t>(i + kHalfRange);
}

}  // namespace

VoxelMap::VoxelMap(double voxel_size) : voxel_(voxel_size) {
  if (!(voxel_size >= 0.0) || !std::isfinite(voxel_size))
    throw std::invalid_argument("voxel size must be >= 0, got " + std::to_string(voxel_size));
}

std::uint64_t VoxelMap::keyOf(float x, float y, float z) const {
  return (packAxis(x, voxel_) << 42) | (packAxis(y, voxel_) << 21) | packAxis(z, voxel_);
}

void VoxelMap::insert(const MapPoint& p) {
  inserted_++;
  if (voxel_ == 0.0) {
    raw_.push_back(p);
    return;
  }
  Cell& c = cells_[keyOf(p.x, p.y, p.z)];
  c.sx += p.x;
  c.sy += p.y;
  c.sz += p.z;
  c.si += p.intensity;
  c.n++;
}

std::uint32_t VoxelMap::countAt(std::uint64_t key) const {
  const auto it = cells_.find(key);
  return it == cells_.end() ? 0 : it->second.n;
}

std::size_t VoxelMap::size() const {
  return voxel_ == 0.0 ? raw_.size() : cells_.size();
}

std::vector<MapPoint> VoxelMap::points() const {
  if (voxel_ == 0.0) return raw_;
  std::vector<std::uint64_t> keys;
  keys.reserve(cells_.size());
  for (const auto& kv : cells_) keys.push_back(kv.first);
  std::sort(keys.begin(), keys.end());
  std::vector<MapPoint> out;
  out.reserve(keys.size());
  for (auto k : keys) {
    const Cell& c = cells_.at(k);
    const double n = c.n;
    out.push_back({static_cast<float>(c.sx / n), static_cast<float>(c.sy / n),
                   static_cast<float>(c.sz / n), static_cast<float>(c.si / n)});
  }
  return out;
}

std::vector<VoxelCentre> VoxelMap::voxels() const {
  std::vector<VoxelCentre> out;
  out.reserve(cells_.size());
  for (const auto& [key, c] : cells_) {
    const double n = c.n;
    out.push_back({key, static_cast<float>(c.sx / n), static_cast<float>(c.sy / n),
                   static_cast<float>(c.sz / n)});
  }
  std::sort(out.begin(), out.end(),
            [](const VoxelCentre& a, const VoxelCentre& b) { return a.key < b.key; });
  return out;
}

}  // namespace dynobj::mapclean
