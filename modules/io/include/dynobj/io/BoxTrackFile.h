// SPDX-License-Identifier: BSD-3-Clause
// The generic box-track file (docs/formats.md, "Box tracks"): human 3-D boxes with track ids, in
// the LiDAR's own frame, for annotations that are not KITTI's (nuScenes-like exports, your own
// tools). CSV, one row per object per sweep:
//   line 1:  sweep,track,class,x,y,z,length,width,height,yaw
//   then:    0,7,car,12.4,-3.1,-0.8,4.5,1.9,1.6,0.12
// sweep = 0-based sweep number in the recording's time order; (x, y, z) = box centre in the
// sensor frame [m] (+X forward, +Y left, +Z up); length along the heading, width across, height
// up [m]; yaw = heading about +Z [rad]. '#' lines and blank lines are skipped.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

namespace dynobj::io {

struct BoxTrackRow {
  std::size_t sweep = 0;
  int track = 0;
  std::string cls;
  Eigen::Vector3d centre{0, 0, 0};  ///< [m] sensor frame
  Eigen::Vector3d size{0, 0, 0};    ///< [m] length, width, height
  double yaw = 0;                   ///< [rad]
};

/// Throws FormatError "<path>:<line>: <problem>" (wrong header, field count, a non-numeric or
/// negative size).
std::vector<BoxTrackRow> readBoxTracks(const std::string& path);

}  // namespace dynobj::io
