// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/Clusterer.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "dynobj/core/Config.h"

namespace dynobj::core {

void ClusteringParams::visit(ParamVisitor& v) {
  v.value("horizontal_distance", horizontal_distance, kPositive);
  v.value("vertical_distance", vertical_distance, kPositive);
  v.value("min_points", min_points, {1, 1000000});
  v.value("weak_min_points", weak_min_points, {0, 1000000});  // >= min_points: none
  v.value("max_points", max_points, {static_cast<double>(min_points), 100000000});
  v.value("max_area", max_area);
  v.value("voxel", voxel);
}

void ClusteringParams::validate() const {
  StageParams::validate();
  requireInRange("max_area", max_area, 0, 1e6);
  requireInRange("voxel", voxel, 0, 0.5 * std::min(horizontal_distance, vertical_distance));
}

Eigen::Vector3d centroidOf(const LidarFrame& f, const std::vector<int>& pixels) {
  Eigen::Vector3d sum(0, 0, 0);
  for (int px : pixels) {
    const cv::Vec3f& p = f.pointAt(px);
    sum += Eigen::Vector3d(p[0], p[1], p[2]);
  }
  return sum / static_cast<double>(std::max<std::size_t>(1, pixels.size()));
}

void computeClusterShape(const LidarFrame& f, Cluster& c) {
  c.min = Eigen::Vector3d::Constant(1e18);
  c.max = Eigen::Vector3d::Constant(-1e18);
  for (int px : c.pixels) {
    const cv::Vec3f& p = f.pointAt(px);
    const Eigen::Vector3d q(p[0], p[1], p[2]);
    c.min = c.min.cwiseMin(q);
    c.max = c.max.cwiseMax(q);
  }
  const double n = static_cast<double>(std::max<std::size_t>(1, c.pixels.size()));
  c.centroid = centroidOf(f, c.pixels);
  Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
  for (int px : c.pixels) {
    const cv::Vec3f& p = f.pointAt(px);
    const Eigen::Vector2d d(p[0] - c.centroid.x(), p[1] - c.centroid.y());
    cov += d * d.transpose();
  }
  cov /= n;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(cov);  // Eq. (22): PCA
  c.main_direction = es.eigenvectors().col(1);                   // largest eigenvalue
  const double l1 = std::max(es.eigenvalues()(1), 0.0), l2 = std::max(es.eigenvalues()(0), 1e-6);
  c.elongation = std::sqrt(l1 / l2);
  double lo = 1e18, hi = -1e18;
  for (int px : c.pixels) {
    const cv::Vec3f& p = f.pointAt(px);
    const double t = (p[0] - c.centroid.x()) * c.main_direction.x() +
                     (p[1] - c.centroid.y()) * c.main_direction.y();
    lo = std::min(lo, t);
    hi = std::max(hi, t);
  }
  c.length = c.pixels.empty() ? 0.0 : hi - lo;
  const Eigen::Vector3d axis(c.main_direction.x(), c.main_direction.y(), 0);
  c.end_a = c.pixels.empty() ? c.centroid : Eigen::Vector3d(c.centroid + lo * axis);
  c.end_b = c.pixels.empty() ? c.centroid : Eigen::Vector3d(c.centroid + hi * axis);
}

Clusterer::Clusterer(const ClusteringParams& p) : p_(p) {
  p_.validate();
}

namespace {

/// 21 bits per axis of a cell index: keys order cells lexicographically by (x, y, z).
std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  const auto k = [](std::int64_t v) {
    return static_cast<std::uint64_t>(v + (1 << 20)) & 0x1FFFFF;
  };
  return (k(x) << 42) | (k(y) << 21) | k(z);
}

/// floor(v * inv) as an integer, inline: without SSE4.1 (Debian's x86-64 baseline) std::floor is
/// a call into libm, a third of the voxel look-up. Points are finite (LidarFrame).
std::int64_t cellOf(float v, double inv) {
  const double x = v * inv;
  const auto t = static_cast<std::int64_t>(x);  // rounds towards zero
  return t - static_cast<std::int64_t>(x < static_cast<double>(t));
}

constexpr std::uint64_t kEmptySlot = ~std::uint64_t{0};  ///< cellKey() never makes it (63 bits)

/// Union-find root with path halving.
int root(std::vector<int>& parent, int x) {
  while (parent[static_cast<std::size_t>(x)] != x)
    x = parent[static_cast<std::size_t>(x)] =
        parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(x)])];
  return x;
}

void unite(std::vector<int>& parent, int i, int j) {
  const int a = root(parent, i), b = root(parent, j);
  if (a != b) parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
}

/// Sorts (cell key, index) pairs as std::sort would (by key, then index: the input is in index
/// order), in three stable counting passes, one per 21-bit axis field of the key from z to x,
/// each over the cells that field spans in this frame: O(n) where a comparison sort took a fifth
/// of the clustering on real sweeps.
void sortByCell(std::vector<std::pair<std::uint64_t, int>>& cells,
                std::vector<std::pair<std::uint64_t, int>>& tmp, std::vector<int>& counts) {
  if (cells.size() < 2) return;
  tmp.resize(cells.size());
  for (int shift = 0; shift <= 42; shift += 21) {
    const auto field = [shift](std::uint64_t key) {
      return static_cast<std::int64_t>((key >> shift) & 0x1FFFFF);
    };
    std::int64_t lo = field(cells[0].first), hi = lo;
    for (const auto& c : cells) {
      lo = std::min(lo, field(c.first));
      hi = std::max(hi, field(c.first));
    }
    if (lo == hi) continue;
    counts.assign(static_cast<std::size_t>(hi - lo + 2), 0);
    for (const auto& c : cells) counts[static_cast<std::size_t>(field(c.first) - lo + 1)]++;
    for (std::size_t k = 1; k < counts.size(); k++) counts[k] += counts[k - 1];
    for (const auto& c : cells)
      tmp[static_cast<std::size_t>(counts[static_cast<std::size_t>(field(c.first) - lo)]++)] = c;
    cells.swap(tmp);
  }
}

}  // namespace

void Clusterer::cluster(const LidarFrame& f, const cv::Mat_<std::uint8_t>& features,
                        std::vector<Cluster>& out, std::vector<Cluster>* weak,
                        std::vector<int>* dropped) {
  out.clear();
  if (weak) weak->clear();
  if (dropped) dropped->clear();
  pixels_.clear();
  pts_.clear();
  const int n_px = f.rows() * f.cols();
  const std::uint8_t* m = features.ptr<std::uint8_t>(0);
  const std::uint8_t* v = f.valid.ptr<std::uint8_t>(0);
  for (int i = 0; i < n_px; i++)
    if (m[i] && v[i]) pixels_.push_back(i);
  if (pixels_.empty()) return;
  std::vector<int>& label = label_;
  voxels_.clear();
  clusterPoints(f, label);
  const bool by_area = p_.max_area > 0 && p_.voxel > 0;
  const auto max_voxels = static_cast<int>(p_.max_area / (p_.voxel * p_.voxel));
  // Gather the components (labels are union-find roots) and keep those of a plausible size.
  count_.assign(pixels_.size(), 0);
  for (int l : label) count_[static_cast<std::size_t>(l)]++;
  slot_.assign(pixels_.size(), -1);
  const int weak_min =
      weak && p_.weak_min_points > 0 ? std::min(p_.weak_min_points, p_.min_points) : p_.min_points;
  for (std::size_t i = 0; i < pixels_.size(); i++) {
    const auto l = static_cast<std::size_t>(label[i]);
    if (count_[l] < weak_min) continue;
    if (count_[l] > p_.max_points || (by_area && voxels_[l] > max_voxels)) {
      if (dropped) dropped->push_back(pixels_[i]);
      continue;
    }
    std::vector<Cluster>& dst = count_[l] < p_.min_points ? *weak : out;
    if (slot_[l] < 0) {
      slot_[l] = static_cast<int>(dst.size());
      dst.emplace_back();
      dst.back().pixels.reserve(static_cast<std::size_t>(count_[l]));
    }
    dst[static_cast<std::size_t>(slot_[l])].pixels.push_back(pixels_[i]);
  }
  for (Cluster& c : out) computeClusterShape(f, c);
  if (weak)  // the centroid only: the association needs no more
    for (Cluster& c : *weak) c.centroid = centroidOf(f, c.pixels);
}

void Clusterer::clusterPoints(const LidarFrame& f, std::vector<int>& label) {
  const float zs = static_cast<float>(p_.horizontal_distance / p_.vertical_distance);
  // With voxel > 0, the search holds one representative point per voxel (the first feature in
  // it): dense surfaces give many features per voxel, and linking at eps_xy = 0.35 m does not
  // need 10 cm detail. Every feature takes its voxel's cluster.
  std::vector<int>& rep_of = rep_of_;
  rep_of.resize(pixels_.size());
  pts_.clear();
  if (p_.voxel > 0) {
    // Voxel -> representative through an open-addressing hash table (no sort: O(n)).
    std::size_t cap = 64;
    while (cap < 2 * pixels_.size()) cap *= 2;
    const int shift = 64 - static_cast<int>(std::log2(static_cast<double>(cap)));
    slot_key_.assign(cap, kEmptySlot);
    slot_rep_.resize(cap);
    const double inv = 1.0 / p_.voxel;
    std::uint64_t last_key = kEmptySlot;  // pixels in a row are often in the previous one's voxel
    for (std::size_t i = 0; i < pixels_.size(); i++) {
      const cv::Vec3f& p = f.pointAt(pixels_[i]);
      const std::uint64_t key = cellKey(cellOf(p[0], inv), cellOf(p[1], inv), cellOf(p[2], inv));
      if (key == last_key) {  // no look-up in the (large, scattered) table
        rep_of[i] = rep_of[i - 1];
        continue;
      }
      last_key = key;
      std::size_t h = (key * 0x9E3779B97F4A7C15ull) >> shift;
      while (slot_key_[h] != kEmptySlot && slot_key_[h] != key) h = (h + 1) & (cap - 1);
      if (slot_key_[h] == kEmptySlot) {  // first feature of its voxel: the representative
        slot_key_[h] = key;
        slot_rep_[h] = static_cast<int>(pts_.size());
        pts_.emplace_back(p[0], p[1], p[2] * zs);
      }
      rep_of[i] = slot_rep_[h];
    }
  } else {
    for (std::size_t i = 0; i < pixels_.size(); i++) {
      const cv::Vec3f& p = f.pointAt(pixels_[i]);
      pts_.emplace_back(p[0], p[1], p[2] * zs);
      rep_of[i] = static_cast<int>(i);
    }
  }
  std::vector<int>& parent = parent_;
  parent.resize(pts_.size());
  for (std::size_t i = 0; i < parent.size(); i++) parent[i] = static_cast<int>(i);
  linkGrid(parent);
  // Labels must be feature indices (roots of the features' own components) for cluster().
  std::vector<int>& first_feature = first_feature_;
  first_feature.assign(pts_.size(), -1);
  label.resize(pixels_.size());
  for (std::size_t i = 0; i < pixels_.size(); i++) {
    const auto r = static_cast<std::size_t>(root(parent, rep_of[i]));
    if (first_feature[r] < 0) first_feature[r] = static_cast<int>(i);
    label[i] = first_feature[r];
  }
  if (p_.voxel > 0) {  // each representative is one voxel of its component
    voxels_.assign(pixels_.size(), 0);
    for (std::size_t r = 0; r < pts_.size(); r++)
      voxels_[static_cast<std::size_t>(
          first_feature[static_cast<std::size_t>(root(parent, static_cast<int>(r)))])]++;
  }
}

void Clusterer::linkGrid(std::vector<int>& parent) {
  // Cells of side eps in the scaled space: Eq. (6)-(7) neighbours lie in the same or an adjacent
  // cell. Sorted by key, a column (x, y, z-1..z+1) is one contiguous run, and the 4 forward
  // columns' start keys grow with the cell key, so 4 cursors walk the array once: O(n).
  const float eps = static_cast<float>(p_.horizontal_distance), eps2 = eps * eps;
  const double inv = 1.0 / eps;
  cells_.clear();
  for (std::size_t i = 0; i < pts_.size(); i++)
    cells_.emplace_back(
        cellKey(cellOf(pts_[i].x(), inv), cellOf(pts_[i].y(), inv), cellOf(pts_[i].z(), inv)),
        static_cast<int>(i));
  sortByCell(cells_, cells_tmp_, counts_);
  // Link in sorted order (points and union-find contiguous for the scans below), then map back.
  const std::size_t n = cells_.size();
  spts_.resize(n);
  sparent_.resize(n);
  for (std::size_t k = 0; k < n; k++) {
    spts_[k] = pts_[static_cast<std::size_t>(cells_[k].second)];
    sparent_[k] = static_cast<int>(k);
  }
  const auto near = [&](std::size_t a, std::size_t b) {
    const Eigen::Vector3f& p = spts_[a];
    const Eigen::Vector3f& q = spts_[b];
    const float dx = q.x() - p.x(), dy = q.y() - p.y();
    return dx * dx + dy * dy <= eps2 && std::abs(q.z() - p.z()) <= eps;
  };
  const auto linkIfNear = [&](std::size_t a, std::size_t b) {
    if (near(a, b)) unite(sparent_, static_cast<int>(a), static_cast<int>(b));
  };
  constexpr std::uint64_t X = std::uint64_t{1} << 42, Y = std::uint64_t{1} << 21;
  // Forward columns (dx, dy) in {(0,1), (1,-1), (1,0), (1,1)}, each spanning dz = -1..+1.
  const std::uint64_t offset[4] = {Y, X - Y, X, X + Y};
  std::size_t cursor[4] = {0, 0, 0, 0};
  for (std::size_t s = 0; s < n;) {
    const std::uint64_t key = cells_[s].first;
    std::size_t e = s;
    while (e < n && cells_[e].first == key) e++;
    std::size_t up = e;  // the cell above, (0, 0, +1), if any, starts right after this one
    while (up < n && cells_[up].first == key + 1) up++;
    for (std::size_t a = s; a < e; a++)
      for (std::size_t b = a + 1; b < up; b++) linkIfNear(a, b);  // same cell and the one above
    // A cell whose points are already one component (dense surfaces, most cells) links a
    // neighbour point once: not at all when it is in that component already, else through the
    // first of the cell's points near it. The components are the same.
    bool one = e - s >= 2;
    for (std::size_t a = s + 1; one && a < e; a++)
      one = root(sparent_, static_cast<int>(a)) == root(sparent_, static_cast<int>(s));
    for (int k = 0; k < 4; k++) {
      const std::uint64_t lo = key + offset[k] - 1, hi = key + offset[k] + 1;
      std::size_t& c = cursor[k];
      while (c < n && cells_[c].first < lo) c++;
      for (std::size_t b = c; b < n && cells_[b].first <= hi; b++) {
        if (!one) {
          for (std::size_t a = s; a < e; a++) linkIfNear(a, b);
        } else if (root(sparent_, static_cast<int>(b)) != root(sparent_, static_cast<int>(s))) {
          for (std::size_t a = s; a < e; a++)
            if (near(a, b)) {
              unite(sparent_, static_cast<int>(a), static_cast<int>(b));
              break;
            }
        }
      }
    }
    s = e;
  }
  // Each point's parent: the original index of its sorted root (a root maps to itself).
  for (std::size_t k = 0; k < n; k++)
    parent[static_cast<std::size_t>(cells_[k].second)] =
        cells_[static_cast<std::size_t>(root(sparent_, static_cast<int>(k)))].second;
}

}  // namespace dynobj::core
