// SPDX-License-Identifier: BSD-3-Clause
// Point list -> LidarFrame. Two paths:
//  - project(): an *unordered* cloud through the spherical projection of Eq. (1) of Du & Beltrame;
//  - organize(): a cloud that already carries (row, col) per point (no re-projection).
// Rules (docs/formats.md): two points in one pixel -> the pixel shows the nearer one and both map
// to it; a point outside the vertical field of view, or with a non-finite / zero position, is not
// in the image (point_pixel = -1) and is counted in the stats.
#pragma once

#include <algorithm>
#include <cmath>
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
  /// Inline: the map cleaner's free-space check calls it for every voxel of every checked scan.
  inline bool pixelOf(double x, double y, double z, int& row, int& col) const;

  /// Unordered cloud -> frame via Eq. (1). `frame` is reset to the sensor's size.
  ProjectionStats project(const PointCloud& cloud, LidarFrame& frame) const;
  /// Organized cloud (row/col per point) -> frame. Throws std::invalid_argument naming the first
  /// point whose row/col lies outside the image. Two points in one pixel: the nearer holds it;
  /// but a point marked in `second_pass` (a sector the sweep scanned again, later) only takes a
  /// pixel no earlier point holds. Every point maps to its pixel either way.
  ProjectionStats organize(const PointCloud& cloud, LidarFrame& frame,
                           const std::vector<std::uint8_t>* second_pass = nullptr) const;

 private:
  /// Bound [rad] on the error of fastAtan2 (measured: 1.7e-6 rad; the pixelOf oracle test places
  /// points at fractions of this bound from the column edges).
  static constexpr double kFastAtan2Error = 5e-6;
  /// pixelOf: a sine this near a row edge takes the exact path (asin is accurate to ~1e-16).
  static constexpr double kSineMargin = 1e-9;
  /// pixelOf: bins of the sine of elevation over [-1, 1], each knowing the edges above it.
  static constexpr std::size_t kSineBins = 4096;
  /// atan2(y, x) to within kFastAtan2Error: an odd minimax polynomial of atan on [0, 1], folded
  /// into the four quadrants. (0, 0) gives 0.
  static double fastAtan2(double y, double x) {
    const double ax = std::abs(x), ay = std::abs(y), mx = std::max(ax, ay);
    if (mx == 0.0) return 0.0;
    const double a = std::min(ax, ay) / mx, s = a * a;
    double t =
        a * (0.99997726 +
             s * (-0.33262347 +
                  s * (0.19354346 + s * (-0.11643287 + s * (0.05265332 + s * -0.01172120)))));
    if (ay > ax) t = M_PI_2 - t;
    if (x < 0) t = M_PI - t;
    return y < 0 ? -t : t;
  }

  SensorModel sensor_;
  double fov_up_ = 0;                     ///< beta_up [rad]
  double fov_span_ = 0;                   ///< beta_fov [rad]
  std::vector<double> row_upper_edges_;   ///< non-uniform sensors: upper edge of each row
  double lower_edge_ = 0;                 ///< non-uniform sensors: lower edge of the last row
  std::vector<double> sin_edges_;         ///< sine of every row edge, top to bottom (rows + 1)
  std::vector<std::uint16_t> sine_bins_;  ///< per bin of sines: how many edges lie above it
  double column_margin_ = 0;              ///< pixelOf: columns this near an edge take atan2
};

bool SphericalProjection::pixelOf(double x, double y, double z, int& row, int& col) const {
  row = col = -1;
  const double r = std::sqrt(x * x + y * y + z * z);
  if (!(r > 0.0) || !std::isfinite(r)) return false;
  const double s = std::clamp(z / r, -1.0, 1.0);
  // Row: the edges' sines descend; k = how many are >= s, found from the bin of s (edges above
  // the bin) and a step or two through the edges inside it. Row k - 1 lies between
  // sin_edges_[k - 1] and sin_edges_[k].
  const auto bins = static_cast<int>(sine_bins_.size());
  const int bin = std::min(static_cast<int>((s + 1.0) * 0.5 * bins), bins - 1);
  const auto n_edges = sin_edges_.size();
  std::size_t k = sine_bins_[static_cast<std::size_t>(bin)];
  while (k < n_edges && sin_edges_[k] >= s) k++;
  const double above = k > 0 ? sin_edges_[k - 1] - s : 1.0;
  const double below = k < n_edges ? s - sin_edges_[k] : 1.0;
  int v = -1;
  if (std::min(above, below) < kSineMargin)
    v = rowOfElevation(std::asin(s));  // on an edge: the exact rule decides
  else if (k > 0 && k < n_edges)
    v = static_cast<int>(k) - 1;
  if (v < 0) return false;
  // Column: Eq. (1) with the polynomial arctangent, or atan2 within its error of an edge.
  const double u = (fastAtan2(y, x) + M_PI) * (sensor_.cols / (2.0 * M_PI));
  const int c = static_cast<int>(u);  // floor: u >= 0 but for the polynomial's error at -pi
  const double frac = u - c;          // < 0 there, so that column takes the exact path
  row = v;
  col = frac < column_margin_ || frac > 1.0 - column_margin_ ? columnOf(x, y) : c;
  return true;
}

}  // namespace dynobj::core
