// SPDX-License-Identifier: BSD-3-Clause
// CObservationVelodyneScan: laser_id -> row (through the scan's own calibration), azimuth of the
// point -> column by Eq. (1). Uses point_cloud when present (that is what map insertion uses),
// otherwise generates it with MRPT's default parameters, exactly as CPointsMap insertion does.
#include <dynobj/core/RowRecovery.h>
#include <dynobj/core/SphericalProjection.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <algorithm>
#include <cmath>

#include "detail.h"

namespace dynobj::mrptio::detail {
namespace {

using mrpt::obs::CObservationVelodyneScan;

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"  // MRPT's wrapper base has no virtual dtor
/// Receives MRPT's generated points straight into a core::PointCloud (rows mapped later).
struct CloudSink : public CObservationVelodyneScan::PointCloudStorageWrapper {
  core::PointCloud& cloud;
  std::vector<std::uint16_t>& laser;
  CloudSink(core::PointCloud& c, std::vector<std::uint16_t>& l) : cloud(c), laser(l) {}
  void reserve(std::size_t n) override {
    cloud.reserve(n, true, true);
    laser.reserve(n);
  }
  void add_point(float x, float y, float z, std::uint8_t intensity,
                 const mrpt::system::TTimeStamp& /*tim*/, float /*azimuth*/,
                 std::uint16_t laser_id) override {
    cloud.push_back(x, y, z, intensity);
    laser.push_back(laser_id);
  }
};
#pragma GCC diagnostic pop

}  // namespace

core::ProjectionStats convertVelodyne(const CObservationVelodyneScan& o, const OptSensor& sensor,
                                      core::LidarFrame& frame) {
  core::SensorModel model;
  const auto& cal = o.calibration.laser_corrections;
  if (!cal.empty()) {
    model.model = "Velodyne (" + std::to_string(cal.size()) + " lasers, scan calibration)";
    model.rows = static_cast<int>(cal.size());
    model.beam_elevations.clear();
    for (const auto& lc : cal)
      model.beam_elevations.push_back(lc.verticalCorrection * M_PI / 180.0);
  } else if (sensor) {
    model = *sensor;
  } else {
    fail(o, "has no laser calibration; pass a sensor model (e.g. share/dynobj/sensors/vlp-16.ini)");
  }
  if (sensor) {
    if (sensor->rows != model.rows)
      fail(o, "has " + std::to_string(model.rows) + " lasers but the sensor model '" +
                  sensor->model + "' has " + std::to_string(sensor->rows) + " rows");
    model.cols = sensor->cols;
    model.min_range = sensor->min_range;
    model.max_range = sensor->max_range;
  }
  model.max_range = std::max(model.max_range, static_cast<double>(o.maxRange));

  core::PointCloud cloud;
  std::vector<std::uint16_t> laser;
  if (o.point_cloud.size() > 0) {
    const auto& pc = o.point_cloud;
    const std::size_t n = pc.x.size();
    if (pc.y.size() != n || pc.z.size() != n || pc.intensity.size() != n || pc.laser_id.size() != n)
      fail(o, "point_cloud vectors x/y/z/intensity/laser_id have different lengths");
    cloud.reserve(n, true, true);
    for (std::size_t i = 0; i < n; i++) {
      cloud.push_back(pc.x[i], pc.y[i], pc.z[i], pc.intensity[i]);
      laser.push_back(static_cast<std::uint16_t>(pc.laser_id[i]));
    }
  } else {
    if (o.scan_packets.empty()) fail(o, "is empty (no packets and no point cloud)");
    CloudSink sink(cloud, laser);
    // generatePointCloud(dest, params) only writes into `dest`; MRPT declares it non-const.
    const_cast<CObservationVelodyneScan&>(o).generatePointCloud(sink);
  }

  // MRPT 2.5.8 decodes only the first of the two firings in each VLP-16 block, so its VLP-16
  // clouds have 0.4 deg steps: 900 columns at 10 Hz, not the sensor's 1800.
  if (!sensor) model.cols = core::estimateColumns(cloud, laser, model.rows);
  const auto laser_to_row = model.laserToRow();
  const core::SphericalProjection eq1(model);
  cloud.row.resize(cloud.size());
  cloud.col.resize(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); i++) {
    if (laser[i] >= laser_to_row.size())
      fail(o, "point " + std::to_string(i) + " has laser_id " + std::to_string(laser[i]) +
                  " but the calibration has " + std::to_string(laser_to_row.size()) + " lasers");
    cloud.row[i] = static_cast<std::uint16_t>(laser_to_row[laser[i]]);
    cloud.col[i] = static_cast<std::uint16_t>(eq1.columnOf(cloud.x[i], cloud.y[i]));
  }
  return organizeOrFail(o, model, cloud, frame);
}

}  // namespace dynobj::mrptio::detail
