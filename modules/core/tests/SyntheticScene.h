// SPDX-License-Identifier: BSD-3-Clause
// Test helper: tiny analytic scenes rendered into LidarFrames (a floor, a round room, vertical
// cylinders as objects), so stage tests have exact, hand-checkable inputs.
#pragma once

#include <dynobj/core/FrameChain.h>
#include <dynobj/core/FreeSpaceCheck.h>
#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/SphericalProjection.h>

#include <Eigen/Geometry>
#include <cmath>
#include <optional>
#include <vector>

namespace dynobj::test {

struct Post {  ///< a vertical cylinder standing on the floor
  double x, y, radius, height;
  float intensity = 200;
};

struct Scene {
  double floor_z = -1.0;      ///< sensor frame height of the floor (sensor 1 m above it)
  double room_radius = 12.0;  ///< a cylindrical wall around the sensor
  float floor_intensity = 60, wall_intensity = 100;
  std::vector<Post> posts;
  /// Sensor pose in the scene's frame (the scene is drawn in this frame).
  Eigen::Isometry3d sensor = Eigen::Isometry3d::Identity();
};

inline core::SensorModel smallSensor(int rows = 16, int cols = 360) {
  core::SensorModel s;
  s.model = "test";
  s.rows = rows;
  s.cols = cols;
  s.elevation_top = 15 * M_PI / 180;
  s.elevation_bottom = -15 * M_PI / 180;
  s.max_range = 50;
  return s;
}

/// Renders `scene` as seen by a sensor with model `s`: one ray per pixel (row elevation, column
/// centre azimuth), the nearest of floor, wall and posts. Texture: intensity varies with azimuth
/// on the wall (stripes every 10 columns) unless `flat`.
inline core::LidarFrame render(const Scene& scene, const core::SensorModel& s, bool flat = true,
                               std::int64_t stamp = 1) {
  core::PointCloud cloud;
  const auto elev = s.rowElevations();
  const Eigen::Vector3d o = scene.sensor.translation();
  const Eigen::Matrix3d R = scene.sensor.linear();
  for (int r = 0; r < s.rows; r++)
    for (int c = 0; c < s.cols; c++) {
      const double az = -M_PI + (c + 0.5) * 2 * M_PI / s.cols,
                   el = elev[static_cast<std::size_t>(r)];
      const Eigen::Vector3d ds(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az),
                               std::sin(el));
      const Eigen::Vector3d d = R * ds;
      double best = 1e9;
      float inten = 0;
      if (d.z() < -1e-9) {  // floor (1 m checker tiles unless flat)
        const double t = (scene.floor_z - o.z()) / d.z();
        if (t > 0 && t < best) {
          best = t;
          const auto tile =
              static_cast<long>(std::floor(o.x() + t * d.x()) + std::floor(o.y() + t * d.y()));
          inten = flat ? scene.floor_intensity : (tile % 2 ? 90.f : 30.f);
        }
      }
      {  // room wall: |o + t d|_xy = R
        const double a = d.x() * d.x() + d.y() * d.y(), b = o.x() * d.x() + o.y() * d.y(),
                     cc = o.x() * o.x() + o.y() * o.y() - scene.room_radius * scene.room_radius;
        const double t = (-b + std::sqrt(std::max(0.0, b * b - a * cc))) / a;
        if (t > 0 && t < best) {
          best = t;
          // Unless flat: random cells of 10 deg x 0.5 m plus finer marks: corners for ORB.
          const double wall_az = std::atan2(o.y() + t * d.y(), o.x() + t * d.x());
          const auto cell = static_cast<long>(std::floor((wall_az + M_PI) / (2 * M_PI) * 36) +
                                              std::floor((o.z() + t * d.z()) / 0.5));
          const auto fine = static_cast<long>(std::floor((wall_az + M_PI) / (2 * M_PI) * 180) * 7 +
                                              std::floor((o.z() + t * d.z()) / 0.2) * 3);
          auto hash = [](long v) {
            return static_cast<int>((static_cast<unsigned long>(v) * 2654435761UL >> 7) % 160);
          };
          inten =
              flat ? scene.wall_intensity : static_cast<float>(40 + hash(cell) + hash(fine) / 4);
        }
      }
      for (const Post& p : scene.posts) {
        const double ox = o.x() - p.x, oy = o.y() - p.y;
        const double a = d.x() * d.x() + d.y() * d.y(), b = ox * d.x() + oy * d.y(),
                     cc = ox * ox + oy * oy - p.radius * p.radius;
        const double disc = b * b - a * cc;
        if (disc < 0 || a < 1e-12) continue;
        const double t = (-b - std::sqrt(disc)) / a;
        const double z = o.z() + t * d.z();
        if (t > 0 && t < best && z >= scene.floor_z && z <= scene.floor_z + p.height)
          best = t, inten = p.intensity;
      }
      if (best > s.max_range) continue;
      const Eigen::Vector3d q = ds * best;
      cloud.push_back(static_cast<float>(q.x()), static_cast<float>(q.y()),
                      static_cast<float>(q.z()), inten, static_cast<std::uint16_t>(r),
                      static_cast<std::uint16_t>(c));
    }
  core::LidarFrame f;
  core::SphericalProjection(s).organize(cloud, f);
  f.timestamp_ns = stamp;
  return f;
}

/// Two frames of a still sensor `s` (the scene `before`, then `after`), chained, the first one
/// remembered by a free-space check with parameters `p`.
struct TwoStillFrames {
  core::LidarFrame f0, f1;
  core::FrameChain chain;
  core::FreeSpaceCheck check;
  TwoStillFrames(const Scene& before, const Scene& after, const core::SensorModel& s,
                 const core::FreeSpaceParams& p = {})
      : f0(render(before, s, true, 1)), f1(render(after, s, true, 2)), check(p) {
    chain.push(0, Eigen::Isometry3d::Identity(), true);
    chain.push(1, Eigen::Isometry3d::Identity(), true);
    check.remember(0, f0);
  }
};

}  // namespace dynobj::test
