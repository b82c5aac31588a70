// SPDX-License-Identifier: BSD-3-Clause
// Embedding the filter in your own MRPT app: every observation goes through the filter (drop
// mode: dynamic points removed) before it is inserted into a point map.
#include <dynobj/mrptio/DynamicObjectFilter.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <mrpt/maps/CSimplePointsMap.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  dynobj::mrptio::DynamicObjectFilter filter(
      {dynobj::mrptio::FilterMode::Drop, "", std::nullopt, {}});
  mrpt::maps::CSimplePointsMap map;
  dynobj::mrptio::RawlogReader rawlog(argv[1]);
  for (dynobj::mrptio::RawlogEntry e; rawlog.next(e);)
    for (auto& obs : e.observations()) {
      filter.filter(obs);           // tags / removes the moving objects' points in place
      map.insertObservation(*obs);  // stock MRPT insertion sees the static points only
    }
  const auto& s = filter.summary();
  std::cout << s.lidar << " LiDAR frames, " << s.dynamic_points
            << " dynamic points removed, map: " << map.size() << " points\n";
  return 0;
}
