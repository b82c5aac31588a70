// SPDX-License-Identifier: BSD-3-Clause
// dropDynamic for the unorganized LiDAR classes (Velodyne scans, point clouds).
#include <cstddef>
#include <string>

#include "dynobj/mrptio/ObservationConverter.h"
#include "dynobj/mrptio/ObservationTagging.h"

namespace dynobj::mrptio {
namespace {

void requireSize(const mrpt::obs::CObservation& o, std::size_t points, std::size_t mask) {
  if (points != mask)
    throw ConversionError(std::string(o.GetRuntimeClass()->className) + " '" + o.sensorLabel +
                          "': point cloud changed size (" + std::to_string(points) +
                          " points, mask of " + std::to_string(mask) + ")");
}

}  // namespace

TagStats dropDynamic(mrpt::obs::CObservationVelodyneScan& obs,
                     const std::vector<std::uint8_t>& point_mask, mrpt::maps::CPointsMap* removed) {
  if (obs.point_cloud.size() == 0) obs.generatePointCloud();
  auto& pc = obs.point_cloud;
  requireSize(obs, pc.size(), point_mask.size());
  TagStats st;
  std::size_t w = 0;
  for (std::size_t i = 0; i < pc.size(); i++) {
    if (point_mask[i]) {
      if (removed) removed->insertPoint(pc.x[i], pc.y[i], pc.z[i]);
      st.points_removed++;
      continue;
    }
    pc.x[w] = pc.x[i];
    pc.y[w] = pc.y[i];
    pc.z[w] = pc.z[i];
    pc.intensity[w] = pc.intensity[i];
    if (!pc.laser_id.empty()) pc.laser_id[w] = pc.laser_id[i];
    if (!pc.timestamp.empty()) pc.timestamp[w] = pc.timestamp[i];
    if (!pc.azimuth.empty()) pc.azimuth[w] = pc.azimuth[i];
    w++;
  }
  pc.x.resize(w), pc.y.resize(w), pc.z.resize(w), pc.intensity.resize(w);
  if (!pc.laser_id.empty()) pc.laser_id.resize(w);
  if (!pc.timestamp.empty()) pc.timestamp.resize(w);
  if (!pc.azimuth.empty()) pc.azimuth.resize(w);
  pc.pointsForLaserID.clear();
  st.pixels = st.points_removed;
  return st;
}

TagStats dropDynamic(mrpt::obs::CObservationPointCloud& obs,
                     const std::vector<std::uint8_t>& point_mask, mrpt::maps::CPointsMap* removed) {
  requireSize(obs, obs.pointcloud ? obs.pointcloud->size() : 0, point_mask.size());
  TagStats st;
  if (!obs.pointcloud) return st;
  const std::vector<bool> del(point_mask.begin(), point_mask.end());
  for (std::size_t i = 0; i < del.size(); i++)
    if (del[i]) {
      if (removed) {
        float x, y, z;
        obs.pointcloud->getPoint(i, x, y, z);
        removed->insertPoint(x, y, z);
      }
      st.points_removed++;
    }
  obs.pointcloud->applyDeletionMask(del);
  st.pixels = st.points_removed;
  return st;
}

}  // namespace dynobj::mrptio
