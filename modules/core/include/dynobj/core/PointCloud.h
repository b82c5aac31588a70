// SPDX-License-Identifier: BSD-3-Clause
// A LiDAR sweep as a plain list of points (structure of arrays, like MRPT's point maps), the input
// of the projection into a LidarFrame. Optional per-point image coordinates make it "organized".
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace dynobj::core {

struct PointCloud {
  /// Sensor-frame coordinates [m]: +X forward, +Y left, +Z up.
  std::vector<float> x, y, z;
  /// Intensity in sensor units (Ouster signal, Velodyne 0-255, ...). Empty = no intensity.
  std::vector<float> intensity;
  /// Image row (beam, 0 = highest) and column (azimuth bin) of each point, for sensors that
  /// already give them. Both empty = unorganized (use SphericalProjection::project).
  std::vector<std::uint16_t> row, col;
  /// Laser id of each point in the sensor's own numbering (a PCD `ring` field, a Velodyne
  /// laser_id), for unorganized clouds. Empty = unknown. Rows are recovered from it by
  /// RowRecovery (the id order need not be the elevation order).
  std::vector<std::uint16_t> ring;

  std::size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
  bool hasIntensity() const { return !intensity.empty(); }
  bool isOrganized() const { return !row.empty(); }
  bool hasRing() const { return !ring.empty(); }

  void clear();
  void reserve(std::size_t n, bool with_intensity, bool organized);
  void push_back(float px, float py, float pz);
  void push_back(float px, float py, float pz, float pi);
  void push_back(float px, float py, float pz, float pi, std::uint16_t prow, std::uint16_t pcol);

  /// Throws std::invalid_argument naming the vector whose length differs from x.
  void validate() const;
};

}  // namespace dynobj::core
