// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/ObservationConverter.h"

#include <dynobj/core/Config.h>

#include "ObservationClasses.h"
#include "dynobj/mrptio/TimeConversion.h"

namespace dynobj::mrptio {

namespace mobs = mrpt::obs;

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
  return detail::findObservationClass(obs) != nullptr;
}

core::ProjectionStats ObservationConverter::convert(const mobs::CObservation& obs,
                                                    core::LidarFrame& frame) const {
  const detail::ObservationClass* cls = detail::findObservationClass(obs);
  if (!cls) {
    std::string names;
    for (const auto& c : detail::observationClasses())
      names += std::string(names.empty() ? "" : ", ") + c.name;
    detail::fail(obs, "is not a LiDAR observation this converter supports (" + names + ")");
  }
  try {
    obs.load();  // externally stored points / images
  } catch (const std::exception& e) {
    detail::fail(obs, std::string("cannot load its externally stored data: ") + e.what());
  }
  const core::ProjectionStats st = cls->convert(obs, {sensor_, learned_}, frame);
  frame.timestamp_ns = toUnixNs(obs.timestamp);
  if (st.input_points == 0) detail::fail(obs, "is empty (no points)");
  return st;
}

}  // namespace dynobj::mrptio
