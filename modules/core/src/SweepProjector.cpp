// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/SweepProjector.h"

#include <algorithm>
#include <cmath>

namespace dynobj::core {
namespace {

/// Fractional intensities (KITTI remission, 0-1) are stored x 255 (the 8-bit scale of the
/// sensor they come from); integer-valued ones (Velodyne 0-255, Ouster 8/16-bit) as they are.
double intensityScaleOf(const PointCloud& c) {
  if (!c.hasIntensity()) return 1.0;
  float hi = 0;
  for (float v : c.intensity)
    if (std::isfinite(v)) hi = std::max(hi, v);
  return hi <= 1.0f ? 255.0 : 1.0;
}

}  // namespace

SweepProjector::SweepProjector(std::optional<SensorModel> sensor)
    : sensor_(std::move(sensor)), hint_(sensor_) {}

void SweepProjector::reset() {
  hint_ = sensor_;
  scale_ = 0;
  lasers_ = 0;
}

ProjectionStats SweepProjector::project(PointCloud& cloud, LidarFrame& frame) {
  if (scale_ == 0) scale_ = intensityScaleOf(cloud);  // once, so every sweep has the same scale
  for (float& v : cloud.intensity) v = static_cast<float>(v * scale_);
  const ProjectionStats stats = projectUnordered(cloud, hint_, frame, &source_, &lasers_);
  if (!hint_ && rowsFromData(source_))
    hint_ = frame.sensor;  // later sweeps keep the first complete sweep's rows
  return stats;
}

}  // namespace dynobj::core
