// SPDX-License-Identifier: BSD-3-Clause
// CObservation3DRangeScan in the organized LiDAR layout of docs/formats.md.
#include <dynobj/core/RowRecovery.h>
#include <dynobj/core/SphericalProjection.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

#include "detail.h"
#include "dynobj/mrptio/RangeScanLayout.h"

namespace dynobj::mrptio::detail {
namespace {

using mrpt::obs::CObservation3DRangeScan;

/// Rows and columns of the scan's images.
void imageSize(const CObservation3DRangeScan& o, int& h, int& w) {
  h = w = 0;
  if (o.hasRangeImage) {
    h = static_cast<int>(o.rangeImage.rows());
    w = static_cast<int>(o.rangeImage.cols());
  } else if (o.hasIntensityImage) {
    h = static_cast<int>(o.intensityImage.getHeight());
    w = static_cast<int>(o.intensityImage.getWidth());
  }
}

/// Per-pixel intensity (H x W float), or empty when the scan has none.
cv::Mat_<float> intensityOf(const CObservation3DRangeScan& o, int h, int w) {
  cv::Mat_<std::uint16_t> raw = intensityLayer(o);
  if (!raw.empty()) {
    if (raw.rows != h || raw.cols != w)
      fail(o, "layer '" + std::string(kIntensityLayer) + "' is " + std::to_string(raw.rows) + "x" +
                  std::to_string(raw.cols) + " but the scan is " + std::to_string(h) + "x" +
                  std::to_string(w));
    cv::Mat_<float> out;
    raw.convertTo(out, CV_32F);
    return out;
  }
  if (!o.hasIntensityImage) return {};
  const cv::Mat& img = o.intensityImage.asCvMatRef();
  if (img.rows != h || img.cols != w)
    fail(o, "intensityImage is " + std::to_string(img.rows) + "x" + std::to_string(img.cols) +
                " but the range image is " + std::to_string(h) + "x" + std::to_string(w));
  cv::Mat gray = img;
  if (img.channels() == 3) cv::cvtColor(img, gray, cv::COLOR_BGR2GRAY);
  cv::Mat_<float> out;
  gray.convertTo(out, CV_32F);
  return out;
}

}  // namespace

core::ProjectionStats convertRangeScan3D(const CObservation3DRangeScan& o, const OptSensor& sensor,
                                         core::LidarFrame& frame) {
  int h = 0, w = 0;
  imageSize(o, h, w);
  if (h == 0 || w == 0)
    fail(o, "has neither a range image nor an intensity image, so its rows x cols are unknown");
  if (sensor && (sensor->rows != h || sensor->cols != w))
    fail(o, "is " + std::to_string(h) + "x" + std::to_string(w) + " but the sensor model '" +
                sensor->model + "' is " + std::to_string(sensor->rows) + "x" +
                std::to_string(sensor->cols));
  const cv::Mat_<float> inten = intensityOf(o, h, w);
  const double max_range = o.maxRange > 1.0f ? static_cast<double>(o.maxRange) : 100.0;
  core::PointCloud cloud;

  if (o.hasPoints3D && !o.points3D_x.empty()) {
    const std::size_t n = o.points3D_x.size();
    if (o.points3D_y.size() != n || o.points3D_z.size() != n)
      fail(o, "points3D_x/y/z have different lengths (" + std::to_string(n) + ", " +
                  std::to_string(o.points3D_y.size()) + ", " + std::to_string(o.points3D_z.size()) +
                  ")");
    const bool organized = o.points3D_idxs_x.size() == n && o.points3D_idxs_y.size() == n;
    if (!organized && !sensor)
      fail(o, "points3D_idxs_x/y do not give a pixel for each of its " + std::to_string(n) +
                  " points; pass a sensor model to project them with Eq. (1)");
    cloud.reserve(n, !inten.empty(), organized);
    for (std::size_t i = 0; i < n; i++) {
      const float x = o.points3D_x[i], y = o.points3D_y[i], z = o.points3D_z[i];
      if (!organized) {
        cloud.push_back(x, y, z);
        continue;
      }
      const std::uint16_t c = o.points3D_idxs_x[i], r = o.points3D_idxs_y[i];
      if (r >= h || c >= w)
        fail(o, "point " + std::to_string(i) + " has pixel (row " + std::to_string(r) + ", col " +
                    std::to_string(c) + ") outside its " + std::to_string(h) + "x" +
                    std::to_string(w) + " image");
      cloud.push_back(x, y, z, inten.empty() ? 0.0f : inten(r, c), r, c);
    }
    if (inten.empty()) cloud.intensity.clear();
    return organizeOrFail(
        o,
        sensor ? *sensor : core::organizedModel(cloud, h, w, max_range, "CObservation3DRangeScan"),
        cloud, frame);
  }

  if (!o.hasRangeImage) fail(o, "has no points3D and no range image");
  if (!sensor)
    fail(o,
         "has no points3D; its range image can only be turned into points with a sensor model "
         "(its pinhole cameraParams cannot describe a 360-degree LiDAR)");
  if (o.range_is_depth)
    fail(o, "has range_is_depth = true (a depth camera); the LiDAR layout stores ranges");
  // Documented fallback: unproject each range with the sensor model (row elevation, column centre).
  const auto elev = sensor->rowElevations();
  cloud.reserve(static_cast<std::size_t>(h) * static_cast<std::size_t>(w), !inten.empty(), true);
  for (int r = 0; r < h; r++) {
    const double el = elev[static_cast<std::size_t>(r)];
    for (int c = 0; c < w; c++) {
      const std::uint16_t raw = o.rangeImage(r, c);
      if (raw == 0) continue;
      const double rng = raw * static_cast<double>(o.rangeUnits);
      const double az = -M_PI + (c + 0.5) * 2.0 * M_PI / w;  // inverse of Eq. (1), column centre
      cloud.push_back(static_cast<float>(rng * std::cos(el) * std::cos(az)),
                      static_cast<float>(rng * std::cos(el) * std::sin(az)),
                      static_cast<float>(rng * std::sin(el)), inten.empty() ? 0.0f : inten(r, c),
                      static_cast<std::uint16_t>(r), static_cast<std::uint16_t>(c));
    }
  }
  if (inten.empty()) cloud.intensity.clear();
  return organizeOrFail(o, *sensor, cloud, frame);
}

}  // namespace dynobj::mrptio::detail
