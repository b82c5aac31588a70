// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/SphericalProjection.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynobj::core {
namespace {

/// Bound [rad] on the error of fastAtan2 below (measured: 1.7e-6 rad; the pixelOf oracle
/// test places points at fractions of this bound from the column edges).
constexpr double kFastAtan2Error = 5e-6;
/// pixelOf: a sine this near a row edge takes the exact path (asin is accurate to ~1e-16).
constexpr double kSineMargin = 1e-9;
/// pixelOf: bins of the sine of elevation over [-1, 1], each knowing the edges above it.
constexpr std::size_t kSineBins = 4096;

/// atan2(y, x) to within kFastAtan2Error: an odd minimax polynomial of atan on [0, 1], folded
/// into the four quadrants. (0, 0) gives 0.
double fastAtan2(double y, double x) {
  const double ax = std::abs(x), ay = std::abs(y), mx = std::max(ax, ay);
  if (mx == 0.0) return 0.0;
  const double a = std::min(ax, ay) / mx, s = a * a;
  double t = a * (0.99997726 +
                  s * (-0.33262347 +
                       s * (0.19354346 + s * (-0.11643287 + s * (0.05265332 + s * -0.01172120)))));
  if (ay > ax) t = M_PI_2 - t;
  if (x < 0) t = M_PI - t;
  return y < 0 ? -t : t;
}

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
