// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/SphericalProjection.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynobj::core {
namespace {

bool finitePoint(float x, float y, float z) {
  return std::isfinite(x) && std::isfinite(y) && std::isfinite(z) &&
         !(x == 0.0f && y == 0.0f && z == 0.0f);
}

/// Intensity of point i (0 when the cloud has none); counts and zeroes bad values.
float sanitizedIntensity(const PointCloud& cloud, std::size_t i, ProjectionStats& st) {
  if (!cloud.hasIntensity()) return 0.0f;
  const float v = cloud.intensity[i];
  if (std::isfinite(v) && v >= 0.0f) return v;
  st.bad_intensity++;
  return 0.0f;
}

/// Puts point i at (r, c) unless a nearer point is already there. Updates the point map.
void insertPoint(const PointCloud& cloud, std::size_t i, int r, int c, LidarFrame& frame,
                 ProjectionStats& st, bool second_pass = false) {
  const float px = cloud.x[i], py = cloud.y[i], pz = cloud.z[i];
  const float rng = std::sqrt(px * px + py * py + pz * pz);
  const float inten = sanitizedIntensity(cloud, i, st);
  frame.point_pixel[i] = frame.pixelIndex(r, c);
  if (frame.isValid(r, c)) {
    st.hidden++;
    // keep the nearer point (ties: the first one); a second pass never replaces the first
    if (second_pass || frame.range(r, c) <= rng) return;
  }
  frame.setPixel(r, c, rng, inten, cv::Vec3f(px, py, pz), static_cast<std::int32_t>(i));
}

void prepare(const PointCloud& cloud, const SensorModel& sensor, LidarFrame& frame,
             ProjectionStats& st) {
  cloud.validate();
  frame.reset(sensor);
  frame.has_intensity = cloud.hasIntensity();
  frame.point_pixel.assign(cloud.size(), -1);
  st.input_points = cloud.size();
}

}  // namespace

std::string ProjectionStats::toString() const {
  std::ostringstream ss;
  ss << input_points << " points -> " << pixels_set << " pixels (" << hidden << " hidden, "
     << outside_fov << " outside FOV, " << invalid << " invalid";
  if (bad_intensity) ss << ", " << bad_intensity << " bad intensities";
  if (second_pass) ss << ", " << second_pass << " scanned twice";
  ss << ")";
  return ss.str();
}

SphericalProjection::SphericalProjection(const SensorModel& sensor) : sensor_(sensor) {
  sensor_.validate();
  fov_up_ = sensor_.fovUp();
  fov_span_ = sensor_.fovSpan();
  if (!sensor_.isUniform()) {
    const auto e = sensor_.rowElevations();
    row_upper_edges_.resize(e.size());
    row_upper_edges_[0] = fov_up_;
    for (std::size_t r = 1; r < e.size(); r++) row_upper_edges_[r] = 0.5 * (e[r - 1] + e[r]);
    lower_edge_ = fov_up_ - fov_span_;
  }
  // Edges beyond +-90 deg (a dome's half beam spacing) hold every elevation on their side: their
  // sine is that of +-90 deg, which keeps the sines descending.
  const int h = sensor_.rows;
  sin_edges_.resize(static_cast<std::size_t>(h) + 1);
  for (int k = 0; k <= h; k++) {
    const double edge = sensor_.isUniform() ? fov_up_ - fov_span_ * k / h
                        : k < h             ? row_upper_edges_[static_cast<std::size_t>(k)]
                                            : lower_edge_;
    sin_edges_[static_cast<std::size_t>(k)] = std::sin(std::clamp(edge, -M_PI_2, M_PI_2));
  }
  // sine_bins_[b]: how many edges lie above bin b of [-1, 1] (the first edge pixelOf tests).
  sine_bins_.resize(kSineBins);
  std::size_t above = sin_edges_.size();
  for (std::size_t b = 0; b < kSineBins; b++) {
    const double hi = -1.0 + 2.0 * static_cast<double>(b + 1) / kSineBins;
    while (above > 0 && sin_edges_[above - 1] <= hi) above--;
    sine_bins_[b] = static_cast<std::uint16_t>(above);
  }
  column_margin_ = (kFastAtan2Error + 1e-12) * sensor_.cols / (2.0 * M_PI);
}

int SphericalProjection::columnOf(double x, double y) const {
  const int w = sensor_.cols;
  // Eq. (1): u = (atan2(y, x) + pi) / (2 pi) * w
  const double u = (std::atan2(y, x) + M_PI) / (2.0 * M_PI) * w;
  if (!std::isfinite(u)) return 0;  // NaN input: callers reject such points anyway
  int col = static_cast<int>(std::floor(u));
  if (col >= w) col -= w;  // atan2 = +pi is the same direction as -pi
  if (col < 0) col = 0;
  return col;
}

int SphericalProjection::rowOfElevation(double elevation) const {
  const int h = sensor_.rows;
  if (sensor_.isUniform()) {
    // Eq. (1): v = (beta_up - elevation) / beta_fov * h
    const double v = (fov_up_ - elevation) / fov_span_ * h;
    if (v < 0.0 || v > h) return -1;
    return std::min(static_cast<int>(std::floor(v)), h - 1);  // bottom edge -> last row
  }
  if (elevation > row_upper_edges_.front() || elevation < lower_edge_) return -1;
  // Row r covers (upper_edge[r+1], upper_edge[r]]; edges are descending.
  const auto it = std::lower_bound(row_upper_edges_.begin(), row_upper_edges_.end(), elevation,
                                   [](double edge, double e) { return edge >= e; });
  const int row = static_cast<int>(it - row_upper_edges_.begin()) - 1;
  return std::clamp(row, 0, h - 1);
}

ProjectionStats SphericalProjection::project(const PointCloud& cloud, LidarFrame& frame) const {
  ProjectionStats st;
  prepare(cloud, sensor_, frame, st);
  for (std::size_t i = 0; i < cloud.size(); i++) {
    if (!finitePoint(cloud.x[i], cloud.y[i], cloud.z[i])) {
      st.invalid++;
      continue;
    }
    int r = -1, c = -1;
    if (!pixelOf(cloud.x[i], cloud.y[i], cloud.z[i], r, c)) {
      st.outside_fov++;
      continue;
    }
    insertPoint(cloud, i, r, c, frame, st);
  }
  st.pixels_set = frame.validCount();
  return st;
}

ProjectionStats SphericalProjection::organize(const PointCloud& cloud, LidarFrame& frame,
                                              const std::vector<std::uint8_t>* second_pass) const {
  if (second_pass && second_pass->size() != cloud.size())
    throw std::invalid_argument("organize(): second_pass does not have one entry per point");
  if (!cloud.isOrganized())
    throw std::invalid_argument("organize(): the cloud has no row/col per point");
  ProjectionStats st;
  prepare(cloud, sensor_, frame, st);
  for (std::size_t i = 0; i < cloud.size(); i++) {
    const int r = cloud.row[i], c = cloud.col[i];
    if (r >= sensor_.rows || c >= sensor_.cols) {
      std::ostringstream ss;
      ss << "point " << i << " has pixel (row " << r << ", col " << c << ") outside the "
         << sensor_.rows << "x" << sensor_.cols << " image";
      throw std::invalid_argument(ss.str());
    }
    if (!finitePoint(cloud.x[i], cloud.y[i], cloud.z[i])) {
      st.invalid++;
      continue;
    }
    const bool again = second_pass && (*second_pass)[i];
    st.second_pass += again;
    insertPoint(cloud, i, r, c, frame, st, again);
  }
  st.pixels_set = frame.validCount();
  return st;
}

}  // namespace dynobj::core
