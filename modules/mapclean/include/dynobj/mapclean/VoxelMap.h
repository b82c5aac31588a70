// SPDX-License-Identifier: BSD-3-Clause
// A point map that grows with the space it covers, not with the number of scans inserted: one
// point per occupied voxel (the centroid of the points inserted into it, with their mean
// intensity). Voxel size 0 keeps every point (no downsampling).
#pragma once

#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace dynobj::mapclean {

/// A map point: world frame [m] and intensity (sensor units).
struct MapPoint {
  float x = 0, y = 0, z = 0, intensity = 0;
};

/// An occupied voxel: its key (VoxelMap::keyOf) and the centroid of its points.
struct VoxelCentre {
  std::uint64_t key = 0;
  float x = 0, y = 0, z = 0;
};

class VoxelMap {
 public:
  /// `voxel_size` [m] >= 0 (0 = keep every point). Throws std::invalid_argument when negative.
  explicit VoxelMap(double voxel_size = 0.0);

  void insert(const MapPoint& p);
  /// Number of map points (occupied voxels, or inserted points with voxel size 0).
  std::size_t size() const;
  std::size_t pointsInserted() const { return inserted_; }
  bool empty() const { return size() == 0; }
  double voxelSize() const { return voxel_; }

  /// The map's points: voxel centroids ordered by voxel index (deterministic), or every inserted
  /// point in insertion order with voxel size 0.
  std::vector<MapPoint> points() const;

  /// Every occupied voxel (key, centroid), ordered by key. Empty with voxel size 0.
  std::vector<VoxelCentre> voxels() const;

  /// Voxel index of a point, packed (21 bits per axis). Throws std::out_of_range beyond
  /// +-2^20 voxels from the origin. Only for voxel size > 0.
  std::uint64_t keyOf(float x, float y, float z) const;

  /// Points inserted into the voxel `key` (0 when empty). Only for voxel size > 0.
  std::uint32_t countAt(std::uint64_t key) const;
  /// Moves to `other` (same voxel size) every voxel for which keep(key, count) is false; returns
  /// how many voxels moved.
  template <class Keep>
  std::size_t moveVoxelsTo(VoxelMap& other, Keep&& keep) {
    std::size_t moved = 0;
    for (auto it = cells_.begin(); it != cells_.end();) {
      if (keep(it->first, it->second.n)) {
        ++it;
        continue;
      }
      Cell& dst = other.cells_[it->first];
      dst.sx += it->second.sx;
      dst.sy += it->second.sy;
      dst.sz += it->second.sz;
      dst.si += it->second.si;
      dst.n += it->second.n;
      it = cells_.erase(it);
      moved++;
    }
    return moved;
  }

 private:
  struct Cell {
    double sx = 0, sy = 0, sz = 0, si = 0;
    std::uint32_t n = 0;
  };
  double voxel_;
  std::unordered_map<std::uint64_t, Cell> cells_;
  std::vector<MapPoint> raw_;
  std::size_t inserted_ = 0;
};

}  // namespace dynobj::mapclean
