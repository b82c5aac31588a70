// SPDX-License-Identifier: BSD-3-Clause
// CObservationPointCloud: any CPointsMap (points in the sensor frame), projected with Eq. (1).
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include "detail.h"

namespace dynobj::mrpt::detail {

core::ProjectionStats convertPointCloud(const ::mrpt::obs::CObservationPointCloud& o,
                                        const OptSensor& sensor, core::LidarFrame& frame) {
  if (!sensor)
    fail(o,
         "needs a sensor model (rows, cols, vertical field of view) to be projected with "
         "Eq. (1); pass one, e.g. share/dynobj/sensors/os0-64.ini");
  if (!o.pointcloud) fail(o, "has no point cloud (pointcloud is null)");
  const auto& pc = *o.pointcloud;
  const auto& xs = pc.getPointsBufferRef_x();
  const auto& ys = pc.getPointsBufferRef_y();
  const auto& zs = pc.getPointsBufferRef_z();
  core::PointCloud cloud;
  const auto* xyzi = dynamic_cast<const ::mrpt::maps::CPointsMapXYZI*>(&pc);
  cloud.reserve(xs.size(), xyzi != nullptr, false);
  cloud.x.assign(xs.begin(), xs.end());
  cloud.y.assign(ys.begin(), ys.end());
  cloud.z.assign(zs.begin(), zs.end());
  if (xyzi) {
    const auto& inten = xyzi->getPointsBufferRef_intensity();
    if (inten.size() == xs.size()) cloud.intensity.assign(inten.begin(), inten.end());
  }
  return organizeOrFail(o, *sensor, cloud, frame);
}

}  // namespace dynobj::mrpt::detail
