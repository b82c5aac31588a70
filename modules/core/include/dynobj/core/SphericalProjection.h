// SPDX-License-Identifier: BSD-3-Clause
// Point list -> LidarFrame. Two paths:
//  - project(): an *unordered* cloud through the spherical projection of Eq. (1) of Du & Beltrame;
//  - organize(): a cloud that already carries (row, col) per point (no re-projection).
// Rules (docs/formats.md): two points in one pixel -> the pixel shows the nearer one and both map
// to it; a point outside the vertical field of view, or with a non-finite / zero position, is not
// in the image (point_pixel = -1) and is counted in the stats.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/PointCloud.h"
#include "dynobj/core/SensorModel.h"

namespace dynobj::core {

/// What happened to the input points of one projection.
struct ProjectionStats {
  std::size_t input_points = 0;   ///< points in the cloud
  std::size_t pixels_set = 0;     ///< pixels holding a return afterwards
  std::size_t hidden = 0;         ///< points behind a nearer point in the same pixel (still mapped)
  std::size_t outside_fov = 0;    ///< points above/below the vertical field of view
  std::size_t invalid = 0;        ///< NaN/inf coordinates or a point at the origin (not mapped)
  std::size_t bad_intensity = 0;  ///< non-finite or negative intensity, stored as 0
  std::size_t second_pass = 0;    ///< points of a sector the sweep scanned again (organize())
  std::string toString() const;
};

class SphericalProjection {
 public:
  /// Validates the sensor model (throws ParameterError naming the bad key).
  explicit SphericalProjection(const SensorModel& sensor);

  const SensorModel& sensor() const { return sensor_; }

  /// Eq. (1), u: column of azimuth atan2(y, x); the seam at +-pi maps to column 0.
  int columnOf(double x, double y) const;
  /// Eq. (1), v: row of an elevation [rad], or -1 outside the vertical FOV. Sensors with a beam
  /// table (non-uniform spacing) use the nearest beam within half the gap to its neighbours.
  int rowOfElevation(double elevation) const;
  /// Sine of the elevation at the middle of `row` (between its edges): the height of a return
  /// in that row is its range times this.
  double sinElevationOfRow(int row) const {
    const auto k = static_cast<std::size_t>(row);
    return 0.5 * (sin_edges_[k] + sin_edges_[k + 1]);
  }
  /// Both at once; false (row = col = -1) when the point is not in the image. The same pixel as
  /// rowOfElevation(asin(z / |p|)) and columnOf(x, y), without their trigonometry: the row is
  /// found among the sines of the row edges and the column from a polynomial arctangent; a point
  /// within the polynomial's error of an edge takes the exact path (docs/performance.md).
  bool pixelOf(double x, double y, double z, int& row, int& col) const;

  /// Unordered cloud -> frame via Eq. (1). `frame` is reset to the sensor's size.
  ProjectionStats project(const PointCloud& cloud, LidarFrame& frame) const;
  /// Organized cloud (row/col per point) -> frame. Throws std::invalid_argument naming the first
  /// point whose row/col lies outside the image. Two points in one pixel: the nearer holds it;
  /// but a point marked in `second_pass` (a sector the sweep scanned again, later) only takes a
  /// pixel no earlier point holds. Every point maps to its pixel either way.
  ProjectionStats organize(const PointCloud& cloud, LidarFrame& frame,
                           const std::vector<std::uint8_t>* second_pass = nullptr) const;

 private:
  SensorModel sensor_;
  double fov_up_ = 0;                     ///< beta_up [rad]
  double fov_span_ = 0;                   ///< beta_fov [rad]
  std::vector<double> row_upper_edges_;   ///< non-uniform sensors: upper edge of each row
  double lower_edge_ = 0;                 ///< non-uniform sensors: lower edge of the last row
  std::vector<double> sin_edges_;         ///< sine of every row edge, top to bottom (rows + 1)
  std::vector<std::uint16_t> sine_bins_;  ///< per bin of sines: how many edges lie above it
  double column_margin_ = 0;              ///< pixelOf: columns this near an edge take atan2
};

}  // namespace dynobj::core
