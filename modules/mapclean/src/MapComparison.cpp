// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapComparison.h"

#include <dynobj/mrptio/SequenceRunner.h>

#include <cmath>
#include <fstream>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <stdexcept>

#include "dynobj/mapclean/PoseSource.h"
#include "dynobj/mapclean/TopDownImage.h"

namespace dynobj::mapclean {

long long ActorPoints::key(const Eigen::Vector3d& p, int dx, int dy, int dz) {
  const auto c = [](double v, int d) {
    return static_cast<long long>(std::floor(v / 0.2)) + d + (1 << 20);
  };
  return (c(p.x(), dx) << 42) | (c(p.y(), dy) << 21) | c(p.z(), dz);
}

void ActorPoints::add(const Eigen::Vector3d& p) {
  cells_[key(p, 0, 0, 0)].push_back(p);
  n_++;
}

bool ActorPoints::onActor(const MapPoint& m) const {
  const Eigen::Vector3d q(m.x, m.y, m.z);
  if (q.z() <= 0.25) return false;
  for (int dx = -1; dx <= 1; dx++)
    for (int dy = -1; dy <= 1; dy++)
      for (int dz = -1; dz <= 1; dz++) {
        const auto it = cells_.find(key(q, dx, dy, dz));
        if (it == cells_.end()) continue;
        for (const auto& p : it->second)
          if ((p - q).squaredNorm() < 0.04) return true;
      }
  return false;
}

ActorPoints ActorPoints::fromSequence(mrptio::FrameSource& source, const std::string& gt_labels,
                                      const std::string& gt_poses) {
  mrptio::SequenceOptions o;
  o.detect = false;
  o.ground_truth = gt_labels;
  o.poses = gt_poses;
  ActorPoints a;
  mrptio::SequenceRunner(source, o).run([&](const mrptio::FrameResult& r) {
    const core::LidarFrame& f = r.frame.frame;
    for (auto px : r.truth->pixels) {
      const cv::Vec3f q = f.xyz(static_cast<int>(px) / f.cols(), static_cast<int>(px) % f.cols());
      a.add(r.pose->pose * Eigen::Vector3d(q[0], q[1], q[2]));
    }
  });
  return a;
}

std::vector<MapPoint> readPointsMapText(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error("cannot read map '" + path + "'");
  std::vector<MapPoint> out;
  for (std::string line; std::getline(f, line);) {
    std::istringstream ss(line);
    double x, y, z;
    if (ss >> x >> y >> z)
      out.push_back({static_cast<float>(x), static_cast<float>(y), static_cast<float>(z), 0.f});
  }
  return out;
}

MapOnActors countOnActors(const std::vector<MapPoint>& map, const ActorPoints& actors) {
  MapOnActors c;
  c.points = map.size();
  for (const MapPoint& p : map) c.on_actors += actors.onActor(p);
  return c;
}

std::vector<bool> onActors(const std::vector<MapPoint>& map, const ActorPoints& actors) {
  std::vector<bool> on(map.size());
  for (std::size_t i = 0; i < map.size(); i++) on[i] = actors.onActor(map[i]);
  return on;
}

std::vector<bool> seenThrough(const std::vector<MapPoint>& map, mrptio::FrameSource& source,
                              const std::string& pose_spec, const VisibilityParams& p,
                              std::string* poses_used) {
  std::vector<VoxelCentre> candidates(map.size());
  for (std::size_t i = 0; i < map.size(); i++) candidates[i] = {i, map[i].x, map[i].y, map[i].z};
  MapVisibilityCheck check(p, std::move(candidates));
  const auto poses = makePoseSource(pose_spec);
  mrptio::SequenceOptions o;  // the detector runs for its ego-motion only
  o.single_sensor = true;
  source.rewind();
  mrptio::SequenceRunner(source, o).run([&](const mrptio::FrameResult& r) {
    check.addScan(r.frame.frame, poses->pose(r.frame, r.detection->ego_motion));
  });
  if (poses_used) *poses_used = poses->describe();
  std::vector<bool> through(map.size(), false);
  for (const std::uint64_t k : check.seenThrough()) through[k] = true;
  return through;
}

cv::Mat renderSideBySide(const std::vector<MapPoint>& left, const std::vector<bool>& left_marked,
                         const std::string& left_caption, const std::vector<MapPoint>& right,
                         const std::vector<bool>& right_marked, const std::string& right_caption,
                         const std::string& marked_means, double resolution) {
  const TopDownView view = TopDownView::fit(left, right, resolution);
  const std::vector<LegendEntry> legend = {{cv::Scalar(200, 200, 200), "map (brighter = higher)"},
                                           {cv::Scalar(0, 0, 255), marked_means}};
  const auto panel = [&](const std::vector<MapPoint>& map, const std::vector<bool>& marked,
                         const std::string& caption) {
    std::vector<MapPoint> still, moving;
    for (std::size_t i = 0; i < map.size(); i++) (marked[i] ? moving : still).push_back(map[i]);
    cv::Mat img = renderTopDown(view, still, moving, 3);
    drawLegendAndScale(img, view, legend);
    cv::Mat out(img.rows + 30, img.cols, CV_8UC3, cv::Scalar(40, 40, 40));
    img.copyTo(out(cv::Rect(0, 30, img.cols, img.rows)));
    cv::putText(out, caption, {8, 21}, cv::FONT_HERSHEY_SIMPLEX, 0.6, {255, 255, 255}, 1);
    return out;
  };
  cv::Mat both;
  cv::Mat gap(view.height + 30, 8, CV_8UC3, cv::Scalar(255, 255, 255));
  cv::hconcat(std::vector<cv::Mat>{panel(left, left_marked, left_caption), gap,
                                   panel(right, right_marked, right_caption)},
              both);
  return both;
}

}  // namespace dynobj::mapclean
