// SPDX-License-Identifier: BSD-3-Clause
// Internal: one converter function per observation class (ObservationConverter dispatches).
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/SensorModel.h>
#include <dynobj/core/SphericalProjection.h>
#include <mrpt/obs/CObservation.h>

#include <map>
#include <optional>
#include <string>

namespace mrpt::obs {
class CObservation3DRangeScan;
class CObservationVelodyneScan;
class CObservationPointCloud;
class CObservationRotatingScan;
}  // namespace mrpt::obs

namespace dynobj::mrptio::detail {

using OptSensor = std::optional<core::SensorModel>;

/// Throws ConversionError("<class> '<label>': <what>").
[[noreturn]] void fail(const mrpt::obs::CObservation& obs, const std::string& what);

/// Runs a projection, turning std::invalid_argument / ParameterError into ConversionError.
core::ProjectionStats organizeOrFail(const mrpt::obs::CObservation& obs,
                                     const core::SensorModel& model, const core::PointCloud& cloud,
                                     core::LidarFrame& frame);

core::ProjectionStats convertRangeScan3D(const mrpt::obs::CObservation3DRangeScan& o,
                                         const OptSensor& sensor, core::LidarFrame& frame);
core::ProjectionStats convertVelodyne(const mrpt::obs::CObservationVelodyneScan& o,
                                      const OptSensor& sensor, core::LidarFrame& frame);
/// `learned`: per sensor label, the rows recovered from its first complete cloud (used as the
/// hint when `sensor` is not given; filled here).
core::ProjectionStats convertPointCloud(const mrpt::obs::CObservationPointCloud& o,
                                        const OptSensor& sensor,
                                        std::map<std::string, core::SensorModel>& learned,
                                        core::LidarFrame& frame);
core::ProjectionStats convertRotatingScan(const mrpt::obs::CObservationRotatingScan& o,
                                          const OptSensor& sensor, core::LidarFrame& frame);

}  // namespace dynobj::mrptio::detail
