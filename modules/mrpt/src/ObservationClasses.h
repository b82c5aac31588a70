// SPDX-License-Identifier: BSD-3-Clause
// Internal: everything this module knows about each MRPT LiDAR observation class, in one table.
// ObservationConverter (isLidarObservation, convert) and DynamicObjectFilter (mark, drop,
// restore) both iterate it. A new class = one entry here + its convert function (detail.h) + its
// tag functions (ObservationTagging.h).
#pragma once

#include <mrpt/maps/CPointsMap.h>
#include <mrpt/obs/CObservation.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "detail.h"
#include "dynobj/mrptio/ObservationTagging.h"

namespace dynobj::mrptio::detail {

struct ConvertContext {
  const OptSensor& sensor;
  std::map<std::string, core::SensorModel>& learned;  ///< rows recovered per sensor label
};

struct ObservationClass {
  const char* name;
  /// Exact class match (stock map insertion dispatches the same way: a subclass is not inserted).
  bool (*is)(const mrpt::obs::CObservation&);
  core::ProjectionStats (*convert)(const mrpt::obs::CObservation&, const ConvertContext&,
                                   core::LidarFrame&);
  /// Tags; null when the class cannot carry them. `pixel_mask`: the frame's dynamic pixels;
  /// `point_mask`: one entry per point of the converted observation.
  TagStats (*mark)(mrpt::obs::CObservation&, const cv::Mat_<std::uint8_t>& pixel_mask);
  TagStats (*drop)(mrpt::obs::CObservation&, const cv::Mat_<std::uint8_t>& pixel_mask,
                   const std::vector<std::uint8_t>& point_mask, mrpt::maps::CPointsMap* removed);
  TagStats (*restore)(mrpt::obs::CObservation&);
  /// Its data lives in external files this project must not rewrite; null: never.
  bool (*externallyStored)(const mrpt::obs::CObservation&);
};

/// The supported classes, in dispatch order.
const std::vector<ObservationClass>& observationClasses();
/// The entry of `obs`'s class, or nullptr for any other observation.
const ObservationClass* findObservationClass(const mrpt::obs::CObservation& obs);

}  // namespace dynobj::mrptio::detail
