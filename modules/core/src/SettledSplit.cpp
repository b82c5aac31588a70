// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/SettledSplit.h"

#include <algorithm>
#include <cmath>

#include "dynobj/core/PointGrid.h"

namespace dynobj::core {
namespace {

/// A shape's points in the scaled space (x, y, z x z_scale) of the clustering (Eq. 6-7).
class ShapeGrid {
 public:
  ShapeGrid(const std::vector<Eigen::Vector3f>& shape, const Eigen::Isometry3d& to_now,
            double radius, double z_scale)
      : grid_(radius), z_scale_(z_scale) {
    for (const Eigen::Vector3f& s : shape) grid_.add(scaled(to_now * s.cast<double>()));
  }
  bool near(const cv::Vec3f& p) const {
    return std::isfinite(grid_.nearestSq(scaled(Eigen::Vector3d(p[0], p[1], p[2]))));
  }

 private:
  Eigen::Vector3d scaled(const Eigen::Vector3d& q) const {
    return {q.x(), q.y(), q.z() * z_scale_};
  }
  PointGrid grid_;
  double z_scale_;
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
                              std::vector<Cluster>& clusters, std::vector<int>& cluster_to_track,
                              std::vector<int>* held) {
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
      auto toResting = [&] {  // the whole cluster to the unseen resting track: the mover coasts
        cluster_to_track[m] = static_cast<int>(s);
        matched[s] = 1;
        resting.push_back(rest.id);
      };
      if (at_rest.pixels.size() < enough) continue;  // the resting object is not in it
      if (mover.pixels.size() < enough) {            // the resting object alone
        if (!unseen.atRest()) continue;              // ... and already with its track
        toResting();
        break;
      }
      // The mover's part must lie where the mover was expected: a walker's lies within
      // centimetres of its prediction, while a false mover's (a tree, a fence) wanders, a resting
      // object that sets off is not at rest any more, and the face of a resting object that a
      // walker hid is not in its last shape.
      // Two objects, each a fair part of the cluster: a sliver is the edge of one of them (a
      // car's end over the place of a small thing it hid, a false mover on a resting object's
      // edge). A walker beside a wall or a parked car is a small part of their cluster too: the
      // mover's part may be small where it matches its prediction closely.
      const std::size_t mover_track = unseen.atRest() ? static_cast<std::size_t>(o) : s;
      const double off =
          (centroidOf(frame, mover.pixels).head<2>() - predicted[mover_track].head<2>()).norm();
      const double sliver = p.min_share * static_cast<double>(clusters[m].pixels.size());
      if (off > p.radius || static_cast<double>(at_rest.pixels.size()) < sliver ||
          (static_cast<double>(mover.pixels.size()) < sliver && off > p.match_radius)) {
        // No split. A cluster that is mostly the resting object is not the mover's to flag: the
        // resting track takes it, the mover coasts (else the association stands).
        const bool majority = p.rest_majority && unseen.atRest() &&
                              2 * at_rest.pixels.size() >= clusters[m].pixels.size();
        if (majority) {
          toResting();
          break;
        }
        // A mover's cluster stays its own; the resting object's fair part in it is not its to flag.
        if (held && p.hold_back && owner.dynamic &&
            static_cast<double>(at_rest.pixels.size()) >= sliver)
          held->insert(held->end(), at_rest.pixels.begin(), at_rest.pixels.end());
        continue;
      }
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
