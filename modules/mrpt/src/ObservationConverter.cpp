// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrpt/ObservationConverter.h"

#include <dynobj/core/Config.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include "detail.h"
#include "dynobj/mrpt/TimeConversion.h"

namespace dynobj::mrpt {

namespace mobs = ::mrpt::obs;

namespace detail {

void fail(const mobs::CObservation& obs, const std::string& what) {
  throw ConversionError(std::string(obs.GetRuntimeClass()->className) + " '" + obs.sensorLabel +
                        "': " + what);
}

core::ProjectionStats organizeOrFail(const mobs::CObservation& obs, const core::SensorModel& model,
                                     const core::PointCloud& cloud, core::LidarFrame& frame) {
  try {
    const core::SphericalProjection projection(model);
    return cloud.isOrganized() ? projection.organize(cloud, frame)
                               : projection.project(cloud, frame);
  } catch (const std::invalid_argument& e) {  // includes core::ParameterError
    fail(obs, e.what());
  }
}

}  // namespace detail

ObservationConverter::ObservationConverter(std::optional<core::SensorModel> sensor)
    : sensor_(std::move(sensor)) {
  if (sensor_) sensor_->validate();
}

bool ObservationConverter::isLidarObservation(const mobs::CObservation& obs) {
  return dynobj_rtti::isClass<mobs::CObservation3DRangeScan>(obs) ||
         dynobj_rtti::isClass<mobs::CObservationVelodyneScan>(obs) ||
         dynobj_rtti::isClass<mobs::CObservationPointCloud>(obs) ||
         dynobj_rtti::isClass<mobs::CObservationRotatingScan>(obs);
}

core::ProjectionStats ObservationConverter::convert(const mobs::CObservation& obs,
                                                    core::LidarFrame& frame) const {
  try {
    obs.load();  // externally stored points / images
  } catch (const std::exception& e) {
    detail::fail(obs, std::string("cannot load its externally stored data: ") + e.what());
  }
  core::ProjectionStats st;
  if (dynobj_rtti::isClass<mobs::CObservation3DRangeScan>(obs))
    st = detail::convertRangeScan3D(dynamic_cast<const mobs::CObservation3DRangeScan&>(obs),
                                    sensor_, frame);
  else if (dynobj_rtti::isClass<mobs::CObservationVelodyneScan>(obs))
    st = detail::convertVelodyne(dynamic_cast<const mobs::CObservationVelodyneScan&>(obs), sensor_,
                                 frame);
  else if (dynobj_rtti::isClass<mobs::CObservationPointCloud>(obs))
    st = detail::convertPointCloud(dynamic_cast<const mobs::CObservationPointCloud&>(obs), sensor_,
                                   learned_, frame);
  else if (dynobj_rtti::isClass<mobs::CObservationRotatingScan>(obs))
    st = detail::convertRotatingScan(dynamic_cast<const mobs::CObservationRotatingScan&>(obs),
                                     sensor_, frame);
  else
    detail::fail(obs,
                 "is not a LiDAR observation this converter supports "
                 "(CObservation3DRangeScan, CObservationVelodyneScan, "
                 "CObservationPointCloud, CObservationRotatingScan)");
  frame.timestamp_ns = toUnixNs(obs.timestamp);
  if (st.input_points == 0) detail::fail(obs, "is empty (no points)");
  return st;
}

}  // namespace dynobj::mrpt
