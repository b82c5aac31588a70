// SPDX-License-Identifier: BSD-3-Clause
// A point map that grows with the space it covers, not with the number of scans inserted: one
// point per occupied voxel (the centroid of the points inserted into it, with their mean
// intensity, and when the last of them came), 40 bytes a slot in one hash table (~50-70 bytes a
// voxel). Voxels can be taken out (extract) once final, so that a map streamed to disk keeps in
// memory only the voxels still in use. Voxel size 0 keeps every point (no downsampling).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
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

  /// Adds a point at time `stamp` (any clock that does not go back: MapCleaner's milliseconds);
  /// true when it opened a new voxel (always with voxel size 0).
  bool insert(const MapPoint& p, std::uint32_t stamp = 0);
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
  static constexpr std::int64_t kHalfRange = std::int64_t{1} << 20;  ///< 21 bits per axis, signed

  /// Points inserted into the voxel `key` (0 when empty). Only for voxel size > 0.
  std::uint32_t countAt(std::uint64_t key) const;
  /// The stamp of the last point inserted into the voxel `key` (0 when empty).
  std::uint32_t lastAt(std::uint64_t key) const;
  bool contains(std::uint64_t key) const { return find(key) != nullptr; }

  /// Views of a voxel counted by MapVisibilityCheck: scans that saw through it, scans that hit it.
  struct Views {
    std::uint16_t free = 0, hit = 0;
  };
  /// Calls fn(x, y, z, views) with the centroid and views of every occupied voxel (any order;
  /// views may be changed). Only for voxel size > 0.
  template <class Fn>
  void forEachVoxel(Fn&& fn) {
    for (Slot& s : slots_)
      if (s.key != kEmpty) visit(s, fn);
  }
  /// The same for the voxels with these keys (absent ones are skipped).
  template <class Fn>
  void forVoxels(const std::vector<std::uint64_t>& keys, Fn&& fn) {
    for (const std::uint64_t key : keys)
      if (Slot* s = find(key)) visit(*s, fn);
  }
  /// A voxel: the running mean of its points as an offset from the voxel's corner (float keeps
  /// sub-micrometre steps there) and of their intensity; 28 bytes.
  struct Cell {
    float dx = 0, dy = 0, dz = 0, intensity = 0;
    std::uint32_t n = 0;
    Views views;
    std::uint32_t last = 0;  ///< stamp of the last point inserted
  };
  /// Open addressing, linear probing: one contiguous array (40 bytes a slot), so a pass over
  /// every voxel (the free-space check, every other scan) streams through memory.
  struct Slot {
    std::uint64_t key = kEmpty;
    Cell cell;
  };
  static constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // keyOf() uses 63 bits

  /// Removes from the map, and returns ordered by key, every voxel for which take(slot) is true
  /// (a pure test: it is asked twice). In place: taking every voxel hands over the table itself,
  /// taking some re-seats the rest; no copy of the map. Nothing with voxel size 0.
  template <class Take>
  std::vector<Slot> extract(Take&& take) {
    std::size_t taken = 0;
    for (const Slot& s : slots_)
      if (s.key != kEmpty && take(s)) taken++;
    std::vector<Slot> out;
    if (taken == 0) return out;
    if (taken == used_) {
      out.swap(slots_);
      out.erase(
          std::remove_if(out.begin(), out.end(), [](const Slot& s) { return s.key == kEmpty; }),
          out.end());
      used_ = 0;
    } else {
      out.reserve(taken);
      std::size_t start = 0;  // empty before the voxels are taken: no probe chain crosses it
      while (slots_[start].key != kEmpty) start++;
      for (Slot& s : slots_)
        if (s.key != kEmpty && take(s)) {
          out.push_back(s);
          s = Slot{};  // empty, and a voxel opened here later starts from nothing
          used_--;
        }
      reseat(start);
    }
    std::sort(out.begin(), out.end(), [](const Slot& a, const Slot& b) { return a.key < b.key; });
    return out;
  }
  /// Adds a voxel of a map of the same voxel size (extract), merged with the one at its key.
  void merge(const Slot& s);
  /// The centroid and mean intensity of a voxel.
  MapPoint centroid(const Slot& s) const {
    double x = 0, y = 0, z = 0;
    corner(s.key, x, y, z);
    return {static_cast<float>(x + s.cell.dx), static_cast<float>(y + s.cell.dy),
            static_cast<float>(z + s.cell.dz), s.cell.intensity};
  }

  /// Moves to `other` (same voxel size) every voxel for which keep(key, count, views) is false;
  /// returns how many voxels moved.
  template <class Keep>
  std::size_t moveVoxelsTo(VoxelMap& other, Keep&& keep) {
    std::vector<Slot> kept;
    kept.reserve(used_);
    std::size_t moved = 0;
    for (const Slot& s : slots_) {
      if (s.key == kEmpty) continue;
      if (keep(s.key, s.cell.n, s.cell.views)) {
        kept.push_back(s);
        continue;
      }
      other.merge(s);
      moved++;
    }
    if (moved) rebuild(kept);
    return moved;
  }

 private:
  Slot* find(std::uint64_t key);
  const Slot* find(std::uint64_t key) const;
  /// The slot of `key`, opened when absent (the table grows at 70 % load).
  Slot& slotFor(std::uint64_t key);
  void rebuild(const std::vector<Slot>& slots);
  /// After slots were emptied: moves every voxel to where a lookup finds it again (in one sweep
  /// from `start`, a slot that was empty before, each to the first free slot from its home), then
  /// shrinks a table under a tenth full.
  void reseat(std::size_t start);
  /// The corner of voxel `key` [m].
  void corner(std::uint64_t key, double& x, double& y, double& z) const {
    constexpr std::uint64_t kAxis = (std::uint64_t{1} << 21) - 1;
    const auto axis = [&](std::uint64_t bits) {
      return static_cast<double>(static_cast<std::int64_t>(bits & kAxis) - kHalfRange) * voxel_;
    };
    x = axis(key >> 42);
    y = axis(key >> 21);
    z = axis(key);
  }

  template <class Fn>
  void visit(Slot& s, Fn& fn) const {
    const MapPoint p = centroid(s);
    fn(p.x, p.y, p.z, s.cell.views);
  }

  double voxel_;
  std::vector<Slot> slots_;  ///< size a power of two (or empty)
  std::size_t used_ = 0;
  std::vector<MapPoint> raw_;
  std::size_t inserted_ = 0;
};

}  // namespace dynobj::mapclean
