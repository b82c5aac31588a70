// SPDX-License-Identifier: BSD-3-Clause
// CObservationPointCloud: any CPointsMap (points in the sensor frame). Rows are recovered from
// the data (core::RowRecovery: firing order, else the elevation histogram, else the sensor
// model's table), columns by Eq. (1).
#include <dynobj/core/RowRecovery.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include "detail.h"

namespace dynobj::mrptio::detail {

core::ProjectionStats convertPointCloud(const mrpt::obs::CObservationPointCloud& o,
                                        const OptSensor& sensor,
                                        std::map<std::string, core::SensorModel>& learned,
                                        core::LidarFrame& frame) {
  if (!o.pointcloud) fail(o, "has no point cloud (pointcloud is null)");
  const auto& pc = *o.pointcloud;
  const auto& xs = pc.getPointsBufferRef_x();
  const auto& ys = pc.getPointsBufferRef_y();
  const auto& zs = pc.getPointsBufferRef_z();
  core::PointCloud cloud;
  const auto* xyzi = dynamic_cast<const mrpt::maps::CPointsMapXYZI*>(&pc);
  cloud.reserve(xs.size(), xyzi != nullptr, false);
  cloud.x.assign(xs.begin(), xs.end());
  cloud.y.assign(ys.begin(), ys.end());
  cloud.z.assign(zs.begin(), zs.end());
  if (xyzi) {
    const auto& inten = xyzi->getPointsBufferRef_intensity();
    if (inten.size() == xs.size()) cloud.intensity.assign(inten.begin(), inten.end());
  }
  const auto known = learned.find(o.sensorLabel);
  const OptSensor hint = sensor || known == learned.end() ? sensor : OptSensor(known->second);
  try {
    core::RowSource source = core::RowSource::NominalTable;
    const core::ProjectionStats st = core::projectUnordered(cloud, hint, frame, &source);
    if (!hint && core::rowsFromData(source)) learned.emplace(o.sensorLabel, frame.sensor);
    return st;
  } catch (const std::invalid_argument& e) {
    fail(o, std::string(e.what()) +
                (sensor ? "" : "; pass one, e.g. share/dynobj/sensors/hdl-64.ini"));
  }
}

}  // namespace dynobj::mrptio::detail
