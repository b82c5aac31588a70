// SPDX-License-Identifier: BSD-3-Clause
// Test helper: a small organized scan with a return on every pixel, as MRPT carries it.
#pragma once

#include <dynobj/core/SphericalProjection.h>
#include <dynobj/mrptio/RangeScanLayout.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <cmath>
#include <cstdint>

namespace dynobj::test {

/// An 8 x 64 scan with a return on every pixel's centre ray (ranges 5..12 m), in the organized
/// layout.
inline mrpt::obs::CObservation3DRangeScan fullScan() {
  core::SensorModel s;
  s.rows = 8;
  s.cols = 64;
  s.elevation_top = 14 * M_PI / 180;
  s.elevation_bottom = -14 * M_PI / 180;
  s.max_range = 50;
  const auto el = s.rowElevations();
  core::PointCloud cloud;
  for (int r = 0; r < 8; r++)
    for (int c = 0; c < 64; c++) {
      const double az = -M_PI + (c + 0.5) * 2 * M_PI / 64, e = el[static_cast<std::size_t>(r)];
      const double d = 5.0 + (r * 64 + c) % 8;
      cloud.push_back(static_cast<float>(d * std::cos(e) * std::cos(az)),
                      static_cast<float>(d * std::cos(e) * std::sin(az)),
                      static_cast<float>(d * std::sin(e)), 100.0f, static_cast<std::uint16_t>(r),
                      static_cast<std::uint16_t>(c));
    }
  core::LidarFrame f;
  core::SphericalProjection(s).organize(cloud, f);
  mrpt::obs::CObservation3DRangeScan o;
  mrptio::frameToRangeScan(f, o);
  o.sensorLabel = "LIDAR";
  return o;
}

}  // namespace dynobj::test
