// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/VoxelMap.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace dynobj::mapclean {
namespace {

std::uint64_t packAxis(double v, double voxel) {
  const auto i = static_cast<std::int64_t>(std::floor(v / voxel));
  if (i < -VoxelMap::kHalfRange || i >= VoxelMap::kHalfRange)
    throw std::out_of_range("point coordinate " + std::to_string(v) +
                            " m is too far from the origin for the voxel map");
  return static_cast<std::uint64_t>(i + VoxelMap::kHalfRange);
}

}  // namespace

VoxelMap::VoxelMap(double voxel_size) : voxel_(voxel_size) {
  if (!(voxel_size >= 0.0) || !std::isfinite(voxel_size))
    throw std::invalid_argument("voxel size must be >= 0, got " + std::to_string(voxel_size));
}

std::uint64_t VoxelMap::keyOf(float x, float y, float z) const {
  return (packAxis(x, voxel_) << 42) | (packAxis(y, voxel_) << 21) | packAxis(z, voxel_);
}

namespace {

std::uint64_t mix(std::uint64_t k) {  // splitmix64's finaliser: neighbouring keys spread out
  k ^= k >> 30;
  k *= 0xbf58476d1ce4e5b9ull;
  k ^= k >> 27;
  k *= 0x94d049bb133111ebull;
  return k ^ (k >> 31);
}

}  // namespace

const VoxelMap::Slot* VoxelMap::find(std::uint64_t key) const {
  if (slots_.empty()) return nullptr;
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = mix(key) & mask;; i = (i + 1) & mask) {
    if (slots_[i].key == key) return &slots_[i];
    if (slots_[i].key == kEmpty) return nullptr;
  }
}

VoxelMap::Slot* VoxelMap::find(std::uint64_t key) {
  return const_cast<Slot*>(static_cast<const VoxelMap*>(this)->find(key));
}

VoxelMap::Slot& VoxelMap::slotFor(std::uint64_t key) {
  if ((used_ + 1) * 10 > slots_.size() * 7) {  // grow: twice the slots, every voxel again
    std::vector<Slot> old;
    old.swap(slots_);
    slots_.assign(std::max<std::size_t>(1024, old.size() * 2), Slot{});
    used_ = 0;
    for (const Slot& s : old)
      if (s.key != kEmpty) slotFor(s.key) = s;
  }
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t i = mix(key) & mask;; i = (i + 1) & mask) {
    if (slots_[i].key == key) return slots_[i];
    if (slots_[i].key == kEmpty) {
      slots_[i].key = key;
      used_++;
      return slots_[i];
    }
  }
}

void VoxelMap::rebuild(const std::vector<Slot>& slots) {
  std::size_t n = 1024;
  while (slots.size() * 10 > n * 7) n *= 2;
  if (n < slots_.size()) std::vector<Slot>().swap(slots_);  // smaller: the memory goes back
  slots_.assign(n, Slot{});
  used_ = 0;
  for (const Slot& s : slots) slotFor(s.key) = s;
}

void VoxelMap::reseat(std::size_t start) {
  const std::size_t n = slots_.size(), mask = n - 1;
  for (std::size_t k = 1; k <= n; k++) {
    const std::size_t i = (start + k) & mask;
    if (slots_[i].key == kEmpty) continue;
    const Slot s = slots_[i];
    slots_[i] = Slot{};
    std::size_t j = mix(s.key) & mask;
    while (slots_[j].key != kEmpty) j = (j + 1) & mask;
    slots_[j] = s;
  }
  if (n > 1024 && used_ * 10 < n) {
    std::vector<Slot> kept;
    kept.reserve(used_);
    for (const Slot& s : slots_)
      if (s.key != kEmpty) kept.push_back(s);
    rebuild(kept);
  }
}

void VoxelMap::merge(const Slot& s) {
  Cell& c = slotFor(s.key).cell;
  const double n = static_cast<double>(c.n) + s.cell.n;
  const auto mean = [&](float a, float b) {
    return static_cast<float>((static_cast<double>(a) * c.n + static_cast<double>(b) * s.cell.n) /
                              n);
  };
  c.dx = mean(c.dx, s.cell.dx);
  c.dy = mean(c.dy, s.cell.dy);
  c.dz = mean(c.dz, s.cell.dz);
  c.intensity = mean(c.intensity, s.cell.intensity);
  c.n += s.cell.n;
  c.last = std::max(c.last, s.cell.last);
}

bool VoxelMap::insert(const MapPoint& p, std::uint32_t stamp) {
  inserted_++;
  if (voxel_ == 0.0) {
    raw_.push_back(p);
    return true;
  }
  const std::uint64_t key = keyOf(p.x, p.y, p.z);
  Cell& c = slotFor(key).cell;
  double x = 0, y = 0, z = 0;
  corner(key, x, y, z);
  c.n++;
  c.last = std::max(c.last, stamp);
  const float w = 1.f / static_cast<float>(c.n);
  c.dx += (static_cast<float>(p.x - x) - c.dx) * w;
  c.dy += (static_cast<float>(p.y - y) - c.dy) * w;
  c.dz += (static_cast<float>(p.z - z) - c.dz) * w;
  c.intensity += (p.intensity - c.intensity) * w;
  return c.n == 1;
}

std::uint32_t VoxelMap::countAt(std::uint64_t key) const {
  const Slot* s = find(key);
  return s ? s->cell.n : 0;
}

std::uint32_t VoxelMap::lastAt(std::uint64_t key) const {
  const Slot* s = find(key);
  return s ? s->cell.last : 0;
}

std::size_t VoxelMap::size() const {
  return voxel_ == 0.0 ? raw_.size() : used_;
}

std::vector<MapPoint> VoxelMap::points() const {
  if (voxel_ == 0.0) return raw_;
  std::vector<const Slot*> order;
  order.reserve(used_);
  for (const Slot& s : slots_)
    if (s.key != kEmpty) order.push_back(&s);
  std::sort(order.begin(), order.end(),
            [](const Slot* a, const Slot* b) { return a->key < b->key; });
  std::vector<MapPoint> out;
  out.reserve(order.size());
  for (const Slot* s : order) out.push_back(centroid(*s));
  return out;
}

std::vector<VoxelCentre> VoxelMap::voxels() const {
  std::vector<VoxelCentre> out;
  out.reserve(used_);
  for (const Slot& s : slots_)
    if (s.key != kEmpty) {
      const MapPoint p = centroid(s);
      out.push_back({s.key, p.x, p.y, p.z});
    }
  std::sort(out.begin(), out.end(),
            [](const VoxelCentre& a, const VoxelCentre& b) { return a.key < b.key; });
  return out;
}

}  // namespace dynobj::mapclean
