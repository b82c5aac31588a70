// SPDX-License-Identifier: BSD-3-Clause
// CObservationRotatingScan (MRPT 2.5: a bare range image, no points, no calibration). Each cell
// becomes a point from the sensor model's beam elevation (scan row = laser id) and the column's
// azimuth; rows are then ordered by elevation and columns re-binned with Eq. (1).
#include <dynobj/core/SphericalProjection.h>
#include <mrpt/obs/CObservationRotatingScan.h>

#include <cmath>

#include "detail.h"

namespace dynobj::mrptio::detail {
namespace {

using mrpt::obs::CObservationRotatingScan;

/// MRPT 2.5's fromVelodyne() writes one column per firing slot (columnCount = slots, only
/// columnCount / rowCount firings used) and a clockwise azimuth with a positive span, unlike the
/// class documentation (span > 0 = counter-clockwise). It labels its output with these models.
bool madeByFromVelodyne(const CObservationRotatingScan& o) {
  return o.lidarModel == "VLP-16" || o.lidarModel == "HDL-32E" || o.lidarModel == "Unknown";
}

}  // namespace

core::ProjectionStats convertRotatingScan(const CObservationRotatingScan& o,
                                          const OptSensor& sensor, core::LidarFrame& frame) {
  if (!sensor)
    fail(o,
         "carries no beam elevations in MRPT 2.5; pass a sensor model whose beam table matches "
         "its rows (e.g. share/dynobj/sensors/vlp-16.ini)");
  const int h = o.rowCount, w = o.columnCount;
  if (h == 0 || w == 0) fail(o, "is empty (rowCount or columnCount is 0)");
  if (sensor->rows != h)
    fail(o, "has " + std::to_string(h) + " rows but the sensor model '" + sensor->model + "' has " +
                std::to_string(sensor->rows));
  if (o.rangeImage.rows() != h || o.rangeImage.cols() != w)
    fail(o, "rangeImage is " + std::to_string(o.rangeImage.rows()) + "x" +
                std::to_string(o.rangeImage.cols()) + " but rowCount x columnCount is " +
                std::to_string(h) + "x" + std::to_string(w));
  const bool has_intensity = o.intensityImage.rows() != 0 || o.intensityImage.cols() != 0;
  if (has_intensity && (o.intensityImage.rows() != h || o.intensityImage.cols() != w))
    fail(o, "intensityImage is " + std::to_string(o.intensityImage.rows()) + "x" +
                std::to_string(o.intensityImage.cols()) + " but the range image is " +
                std::to_string(h) + "x" + std::to_string(w));
  if (!(o.rangeResolution > 0) || !std::isfinite(o.rangeResolution))
    fail(o, "has an invalid rangeResolution " + std::to_string(o.rangeResolution));

  const bool velodyne = madeByFromVelodyne(o) && w % h == 0;
  const double firings = velodyne ? static_cast<double>(w / h) : static_cast<double>(w);
  // Elevation of each scan row: the sensor's per-laser table, or its evenly spaced rows.
  const std::vector<double> elev =
      sensor->isUniform() ? sensor->rowElevations() : sensor->beam_elevations;
  const auto laser_to_row = sensor->laserToRow();
  const core::SphericalProjection eq1(*sensor);

  core::PointCloud cloud;
  cloud.reserve(static_cast<std::size_t>(h) * 64, has_intensity, true);
  for (int r = 0; r < h; r++) {
    const double el = elev[static_cast<std::size_t>(r)];
    for (int c = 0; c < w; c++) {
      const std::uint16_t raw = o.rangeImage(r, c);
      if (raw == 0) continue;
      const double rng = raw * o.rangeResolution;
      const double a = o.startAzimuth + (c + 0.5) * o.azimuthSpan / firings;
      const double az = velodyne ? -a : a;  // counter-clockwise from +X
      const float x = static_cast<float>(rng * std::cos(el) * std::cos(az));
      const float y = static_cast<float>(rng * std::cos(el) * std::sin(az));
      const float z = static_cast<float>(rng * std::sin(el));
      cloud.push_back(x, y, z, has_intensity ? o.intensityImage(r, c) : 0.0f,
                      static_cast<std::uint16_t>(laser_to_row[static_cast<std::size_t>(r)]),
                      static_cast<std::uint16_t>(eq1.columnOf(x, y)));
    }
  }
  if (!has_intensity) cloud.intensity.clear();
  return organizeOrFail(o, *sensor, cloud, frame);
}

}  // namespace dynobj::mrptio::detail
