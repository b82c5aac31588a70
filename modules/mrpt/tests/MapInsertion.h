// SPDX-License-Identifier: BSD-3-Clause
// Test helper: how many points a stock MRPT point map inserts from an observation (what a SLAM
// app's map would get).
#pragma once

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation.h>

#include <cstddef>

namespace dynobj::test {

inline std::size_t insertedPoints(const mrpt::obs::CObservation& o) {
  mrpt::maps::CSimplePointsMap map;
  map.insertionOptions.minDistBetweenLaserPoints = 0;
  map.insertObservation(o);
  return map.size();
}

}  // namespace dynobj::test
