// SPDX-License-Identifier: BSD-3-Clause
// Top-down (bird's-eye) PNG of a map: static points in grey by the highest point of each cell
// (floor dark, walls and objects bright), dynamic points in red on top. Without MRPT (OpenCV).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {

/// The area drawn and the scale, shared by several images of one map so they overlay exactly.
struct TopDownView {
  double min_x = 0, min_y = 0, resolution = 0.05;  ///< [m], [m/px]
  int width = 0, height = 0;                       ///< [px]; +x right, +y up
  double z_ground = 0, z_span = 2.5;               ///< grey scale: z_ground -> dark, +span -> white

  /// Fits every point of both sets with a 1 m margin; coarsens the resolution so that no side
  /// exceeds `max_pixels`. z_ground = 2nd percentile of the heights.
  static TopDownView fit(const std::vector<MapPoint>& a, const std::vector<MapPoint>& b,
                         double resolution = 0.05, int max_pixels = 4000);
};

/// BGR image: black = nothing, grey = static (height), red = dynamic (a disc of
/// `dynamic_radius` pixels around each when > 0, so that a few points show).
cv::Mat renderTopDown(const TopDownView& view, const std::vector<MapPoint>& static_points,
                      const std::vector<MapPoint>& dynamic_points, int dynamic_radius = 0);

/// A colour swatch and what it means, for drawLegendAndScale().
struct LegendEntry {
  cv::Scalar colour;  ///< BGR
  std::string text;
};

/// The length [m] of a scale bar for an image `width_m` wide: the largest 1, 2 or 5 x 10^k that
/// is at most a fifth of the width (at least 0.01 m).
double scaleBarLength(double width_m);

/// Draws on `img` (rendered with `view`): the legend's swatches and texts in the top-left corner
/// and a scale bar of scaleBarLength() metres, labelled, in the bottom-left corner, both on a dark
/// box. Nothing is drawn where the image is too small to hold them (under 160 x 80 px).
void drawLegendAndScale(cv::Mat& img, const TopDownView& view,
                        const std::vector<LegendEntry>& legend);

}  // namespace dynobj::mapclean
