// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/SettledSplit.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace dynobj::core {
namespace {

/// A shape's points on a grid of `radius` cells in the scaled space (x, y, z x z_scale) of the
/// clustering (Eq. 6-7): near() is exact.
class ShapeGrid {
 public:
  ShapeGrid(const std::vector<Eigen::Vector3f>& shape, const Eigen::Isometry3d& to_now,
            double radius, double z_scale)
      : r_(radius), z_scale_(z_scale) {
    for (const Eigen::Vector3f& s : shape) {
      const Eigen::Vector3d q = scaled(to_now * s.cast<double>());
      cells_[key(cell(q.x()), cell(q.y()))].push_back(q);
    }
  }
  bool near(const cv::Vec3f& p) const {
    const Eigen::Vector3d x = scaled(Eigen::Vector3d(p[0], p[1], p[2]));
    const std::int64_t cx = cell(x.x()), cy = cell(x.y());
    for (std::int64_t i = cx - 1; i <= cx + 1; i++)
      for (std::int64_t j = cy - 1; j <= cy + 1; j++) {
        const auto it = cells_.find(key(i, j));
        if (it == cells_.end()) continue;
        for (const Eigen::Vector3d& q : it->second)
          if ((q - x).squaredNorm() <= r_ * r_) return true;
      }
    return false;
  }

 private:
  std::int64_t cell(double v) const { return static_cast<std::int64_t>(std::floor(v / r_)); }
  static std::uint64_t key(std::int64_t i, std::int64_t j) {  // unsigned: no shift of a negative
    return (static_cast<std::uint64_t>(i) << 32) ^ (static_cast<std::uint64_t>(j) & 0xffffffffU);
  }
  Eigen::Vector3d scaled(const Eigen::Vector3d& q) const {
    return {q.x(), q.y(), q.z() * z_scale_};
  }
  double r_, z_scale_;
  std::unordered_map<std::uint64_t, std::vector<Eigen::Vector3d>> cells_;
};

bool reaches(const Cluster& c, const Eigen::Vector3d& p, double margin) {
  return p.x() >= c.min.x() - margin && p.x() <= c.max.x() + margin &&
         p.y() >= c.min.y() - margin && p.y() <= c.max.y() + margin;
}

}  // namespace

std::vector<int> splitSettled(const SettledSplitParams& p, const LidarFrame& frame,
                              long frame_index, const FrameChain& chain,
                              const std::vector<Track>& tracks,
                              const std::vector<Eigen::Vector3d>& predicted,
                              std::vector<Cluster>& clusters, std::vector<int>& cluster_to_track) {
  std::vector<int> resting;  // ids of the resting tracks whose cluster is their part of a merge
  if (p.radius <= 0) return resting;
  std::vector<char> matched(tracks.size(), 0);
  for (int t : cluster_to_track)
    if (t >= 0) matched[static_cast<std::size_t>(t)] = 1;
  const auto enough = static_cast<std::size_t>(std::max(1, p.min_points));
  const std::size_t n = clusters.size();  // parts split off are not split again
  for (std::size_t s = 0; s < tracks.size(); s++) {
    const Track& unseen = tracks[s];
    if (matched[s] || (!unseen.atRest() && !unseen.dynamic)) continue;
    for (std::size_t m = 0; m < n; m++) {
      const int o = cluster_to_track[m];
      if (o < 0 || !reaches(clusters[m], predicted[s], p.margin)) continue;
      const Track& owner = tracks[static_cast<std::size_t>(o)];
      if (unseen.atRest() ? !owner.dynamic : !owner.atRest()) continue;
      const Track& rest = unseen.atRest() ? unseen : owner;
      if (rest.shape.empty() || !chain.contains(rest.shape_frame)) continue;
      const ShapeGrid grid(rest.shape, chain.between(rest.shape_frame, frame_index).inverse(),
                           p.radius, p.z_scale);
      Cluster at_rest, mover;
      for (int px : clusters[m].pixels) {
        const cv::Vec3f& q = frame.pointAt(px);
        (grid.near(q) ? at_rest : mover).pixels.push_back(px);
      }
      if (at_rest.pixels.size() < enough) continue;  // the resting object is not in it
      if (mover.pixels.size() < enough) {            // the resting object alone
        if (!unseen.atRest()) continue;              // ... and already with its track
        cluster_to_track[m] = static_cast<int>(s);   // the mover coasts
        matched[s] = 1;
        resting.push_back(rest.id);
        break;
      }
      // Two objects, each a fair part of the cluster: a sliver is the edge of one of them (a
      // car's end over the place of a small thing it hid, a false mover on a resting object's
      // edge), and the cluster is left as it was.
      const double sliver = p.min_share * static_cast<double>(clusters[m].pixels.size());
      if (static_cast<double>(std::min(at_rest.pixels.size(), mover.pixels.size())) < sliver)
        continue;
      // The mover's part must lie where the mover was expected: a walker's lies within
      // centimetres of its prediction, while a false mover's (a tree, a fence) wanders, a resting
      // object that sets off is not at rest any more, and the face of a resting object that a
      // walker hid is not in its last shape. Else nothing changes.
      const std::size_t mover_track = unseen.atRest() ? static_cast<std::size_t>(o) : s;
      if ((centroidOf(frame, mover.pixels).head<2>() - predicted[mover_track].head<2>()).norm() >
          p.radius)
        continue;
      Cluster& kept = clusters[m];
      kept.pixels = std::move(owner.atRest() ? at_rest.pixels : mover.pixels);
      Cluster part;
      part.pixels = std::move(owner.atRest() ? mover.pixels : at_rest.pixels);
      computeClusterShape(frame, kept);
      computeClusterShape(frame, part);
      clusters.push_back(std::move(part));
      cluster_to_track.push_back(static_cast<int>(s));
      matched[s] = 1;
      resting.push_back(rest.id);
      break;
    }
  }
  return resting;
}

void rememberShapes(const LidarFrame& frame, long frame_index, const std::vector<Cluster>& clusters,
                    const std::vector<int>& keep, std::vector<Track>& tracks) {
  for (Track& t : tracks) {
    if (t.cluster < 0 || std::find(keep.begin(), keep.end(), t.id) != keep.end()) continue;
    t.shape.clear();
    t.shape_frame = -1;
    if (!t.atRest()) continue;
    for (int px : clusters[static_cast<std::size_t>(t.cluster)].pixels) {
      const cv::Vec3f& q = frame.pointAt(px);
      t.shape.emplace_back(q[0], q[1], q[2]);
    }
    t.shape_frame = frame_index;
  }
}

}  // namespace dynobj::core
