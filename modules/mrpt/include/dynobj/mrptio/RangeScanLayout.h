// SPDX-License-Identifier: BSD-3-Clause
// The organized LiDAR layout of CObservation3DRangeScan (docs/formats.md): how this project stores
// a spinning LiDAR sweep in MRPT's stock 3D-scan class so that stock tools read and insert it.
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <mrpt/obs/CObservation3DRangeScan.h>

#include <opencv2/core.hpp>
#include <string>

namespace dynobj::mrptio {

/// rangeImageOtherLayers key holding the full-precision intensity (uint16, sensor units).
inline constexpr const char* kIntensityLayer = "intensity";

/// Writes `frame` into `out` in the organized layout: rangeImage (H x W, rangeUnits chosen so the
/// sensor's max range fits 16 bits), range_is_depth = false, points3D_* = the valid pixels in
/// row-major order with points3D_idxs_x/y = (col, row), an 8-bit intensityImage for viewers and
/// the raw intensity in layer "intensity". timestamp, sensorLabel and sensorPose are left to the
/// caller. Any previous content of `out` (labels, layers) is cleared.
void frameToRangeScan(const core::LidarFrame& frame, mrpt::obs::CObservation3DRangeScan& out);

/// The rangeImageOtherLayers entry `name` as an H x W image (H x W = rangeImage's size), or an
/// empty matrix when absent. Undoes an MRPT 2.5.8 serialization quirk: layers are written as
/// (cols, rows) but read back as (rows, cols), so a deserialized H x W layer arrives as W x H
/// with the same row-major buffer.
cv::Mat_<std::uint16_t> rangeLayer(const mrpt::obs::CObservation3DRangeScan& obs,
                                   const std::string& name);

/// rangeLayer(obs, kIntensityLayer).
inline cv::Mat_<std::uint16_t> intensityLayer(const mrpt::obs::CObservation3DRangeScan& obs) {
  return rangeLayer(obs, kIntensityLayer);
}

}  // namespace dynobj::mrptio
