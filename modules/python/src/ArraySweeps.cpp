// SPDX-License-Identifier: BSD-3-Clause
#include "ArraySweeps.h"

#include <dynobj/core/RowRecovery.h>
#include <dynobj/core/SphericalProjection.h>

#include <cmath>
#include <stdexcept>

namespace dynobj::python {
namespace {

template <class T>
void fillUnordered(const T* p, std::size_t n, core::PointCloud& c) {
  c.clear();
  c.reserve(n, true, false);
  for (std::size_t i = 0; i < n; i++, p += 4)
    c.push_back(static_cast<float>(p[0]), static_cast<float>(p[1]), static_cast<float>(p[2]),
                static_cast<float>(p[3]));
}

/// The pixels with a finite, non-zero position, row-major (a 3D range scan's points3D).
template <class T>
void fillOrganized(const T* p, std::size_t rows, std::size_t cols, core::PointCloud& c) {
  c.clear();
  c.reserve(rows * cols, true, true);
  for (std::size_t r = 0; r < rows; r++)
    for (std::size_t col = 0; col < cols; col++, p += 4) {
      const auto x = static_cast<float>(p[0]), y = static_cast<float>(p[1]),
                 z = static_cast<float>(p[2]);
      if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) ||
          (x == 0.0f && y == 0.0f && z == 0.0f))
        continue;
      c.push_back(x, y, z, static_cast<float>(p[3]), static_cast<std::uint16_t>(r),
                  static_cast<std::uint16_t>(col));
    }
}

std::string seconds(std::int64_t ns) {
  return std::to_string(1e-9 * static_cast<double>(ns));
}

}  // namespace

ArraySweeps::ArraySweeps(std::optional<core::SensorModel> sensor)
    : sensor_(std::move(sensor)), projector_(sensor_) {}

void ArraySweeps::convert(const ArrayView& a, std::int64_t timestamp_ns, mrptio::Frame& f) {
  if (timestamp_ns <= 0)
    throw std::invalid_argument("timestamp: " + seconds(timestamp_ns) + " s, must be > 0");
  if (timestamp_ns <= last_ns_)
    throw std::invalid_argument("timestamp: " + seconds(timestamp_ns) +
                                " s is not after the previous sweep's " + seconds(last_ns_) + " s");
  core::PointCloud& cloud = f.points;
  if (a.organized()) {
    if (a.rows > 65535 || a.cols > 65535)
      throw std::invalid_argument("points: an organized array of " + std::to_string(a.rows) + "x" +
                                  std::to_string(a.cols) + " pixels (at most 65535 x 65535)");
    const int h = static_cast<int>(a.rows), w = static_cast<int>(a.cols);
    if (sensor_ && (sensor_->rows != h || sensor_->cols != w))
      throw std::invalid_argument("points: the organized array is " + std::to_string(h) + "x" +
                                  std::to_string(w) + " but the sensor preset '" + sensor_->model +
                                  "' is " + std::to_string(sensor_->rows) + "x" +
                                  std::to_string(sensor_->cols));
    if (a.is_double)
      fillOrganized(static_cast<const double*>(a.data), a.rows, a.cols, cloud);
    else
      fillOrganized(static_cast<const float*>(a.data), a.rows, a.cols, cloud);
    const core::SensorModel model =
        sensor_ ? *sensor_ : core::organizedModel(cloud, h, w, 100.0, "organized array");
    f.stats = core::SphericalProjection(model).organize(cloud, f.frame);
    cloud.clear();  // the mask is per pixel (maskOf)
  } else {
    if (a.rows == 0) throw std::invalid_argument("points: the array holds no point");
    if (a.is_double)
      fillUnordered(static_cast<const double*>(a.data), a.rows, cloud);
    else
      fillUnordered(static_cast<const float*>(a.data), a.rows, cloud);
    try {
      f.stats = projector_.project(cloud, f.frame);
    } catch (const std::invalid_argument& e) {  // no row rule applies (the tools: "give --sensor")
      throw std::invalid_argument(std::string("points: ") + e.what() +
                                  "; give the sensor preset (sensor=...)");
    }
  }
  f.frame.timestamp_ns = timestamp_ns;
  last_ns_ = timestamp_ns;
  f.index = f.entry = index_++;
  f.where = "sweep " + std::to_string(f.index);
  f.sensor_label = "LIDAR";
}

Mask ArraySweeps::maskOf(const mrptio::Frame& f, const cv::Mat_<std::uint8_t>& dynamic) {
  Mask m;
  if (f.points.empty()) {  // organized (convert() keeps no points): per pixel
    m.rows = static_cast<std::size_t>(dynamic.rows);
    m.cols = static_cast<std::size_t>(dynamic.cols);
    m.values.resize(dynamic.total());
    const std::uint8_t* d = dynamic.ptr<std::uint8_t>(0);
    for (std::size_t i = 0; i < m.values.size(); i++) m.values[i] = d[i] != 0 ? 1 : 0;
    return m;
  }
  m.values = f.frame.pointMaskFromPixelMask(dynamic);
  m.rows = m.values.size();
  return m;
}

}  // namespace dynobj::python
