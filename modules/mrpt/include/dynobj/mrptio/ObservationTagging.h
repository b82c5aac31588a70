// SPDX-License-Identifier: BSD-3-Clause
// Tags on MRPT LiDAR observations (docs/formats.md §4): the building blocks of the observation
// filters, one function per class and tag (the table in src/ObservationClasses.cpp lists them).
// CObservation3DRangeScan in the organized LiDAR layout, from a per-pixel dynamic mask:
//  - mark:    pixelLabels bit named "dynamic" (other labels kept); geometry untouched.
//  - drop:    mark + the dynamic points erased from points3D_* (what stock map insertion reads) and
//             their ranges moved from rangeImage into rangeImageOtherLayers["dynamic"].
//  - restore: undoes drop: ranges back, points re-created on their pixels' rays.
#pragma once

#include <mrpt/maps/CPointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <cstddef>
#include <opencv2/core.hpp>
#include <vector>

namespace dynobj::mrptio {

/// pixelLabels name of the dynamic bit, and the rangeImageOtherLayers key of dropped ranges.
inline constexpr const char* kDynamicLabel = "dynamic";
inline constexpr const char* kDynamicLayer = "dynamic";

struct TagStats {
  std::size_t pixels = 0;           ///< dynamic pixels of the mask that hold a return
  std::size_t points_removed = 0;   ///< drop: points erased from points3D_*
  std::size_t points_restored = 0;  ///< restore: points re-created
};

/// Sets the "dynamic" bit on the mask's pixels (non-zero) and clears it elsewhere, creating
/// pixelLabels (8 bits) if the scan has none. Throws ConversionError when the scan is not in the
/// organized layout, the mask's size differs, or every label bit is taken by other names.
TagStats markDynamic(mrpt::obs::CObservation3DRangeScan& obs, const cv::Mat_<std::uint8_t>& mask);

/// markDynamic(), then removes the mask's points from points3D_* (keeping the five vectors
/// aligned; never zeroing, which stock insertion mishandles) and moves their ranges into the
/// layer "dynamic" (added to what an earlier drop put there).
TagStats dropDynamic(mrpt::obs::CObservation3DRangeScan& obs, const cv::Mat_<std::uint8_t>& mask);

/// Undoes dropDynamic(): the layer's ranges go back into rangeImage and a point is appended for
/// each, on its pixel's ray (row elevation: median of the row's other points; column azimuth: the
/// Eq. 1 column centre). The layer is removed; labels stay. Exact for scans whose points lie on
/// pixel-centre rays (the simulator's); within half a pixel's angle otherwise.
TagStats restoreDynamic(mrpt::obs::CObservation3DRangeScan& obs);

// Unorganized classes, from a per-point mask (one entry per point of the converted observation,
// core::LidarFrame::pointMaskFromPixelMask): drop only (they carry no label channel and keep no
// dropped points to restore). `removed` (optional) receives the dropped points, sensor frame.

/// Removes the mask's points from point_cloud (generated first when empty: stock map insertion
/// reads it when present), keeping its per-point vectors (intensity, laser_id, timestamp,
/// azimuth) aligned. Throws ConversionError when the cloud's size differs from the mask's.
TagStats dropDynamic(mrpt::obs::CObservationVelodyneScan& obs,
                     const std::vector<std::uint8_t>& point_mask,
                     mrpt::maps::CPointsMap* removed = nullptr);

/// Removes the mask's points from the cloud (CPointsMap::applyDeletionMask). Throws
/// ConversionError when the cloud's size differs from the mask's.
TagStats dropDynamic(mrpt::obs::CObservationPointCloud& obs,
                     const std::vector<std::uint8_t>& point_mask,
                     mrpt::maps::CPointsMap* removed = nullptr);

}  // namespace dynobj::mrptio
