// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RangeScanLayout.h"

#include <dynobj/io/FrameImages.h>

#include <algorithm>
#include <cmath>

namespace dynobj::mrptio {
namespace {

/// Smallest of 1, 2, 4, 10 mm per unit that stores `max_range` in 16 bits.
float rangeUnitsFor(double max_range) {
  for (float u : {0.001f, 0.002f, 0.004f, 0.01f})
    if (max_range <= 65535.0 * u) return u;
  return 0.02f;
}

}  // namespace

void frameToRangeScan(const core::LidarFrame& frame, mrpt::obs::CObservation3DRangeScan& out) {
  const int h = frame.rows(), w = frame.cols();
  double max_seen = 0;
  cv::minMaxLoc(frame.range, nullptr, &max_seen);
  out.rangeImageOtherLayers.clear();
  out.pixelLabels.reset();
  out.hasConfidenceImage = false;
  out.range_is_depth = false;
  out.maxRange = static_cast<float>(frame.sensor.max_range);
  out.rangeUnits = rangeUnitsFor(std::max(max_seen, frame.sensor.max_range));
  out.cameraParams.ncols = static_cast<uint32_t>(w);  // size only: never re-project with it
  out.cameraParams.nrows = static_cast<uint32_t>(h);
  out.cameraParamsIntensity = out.cameraParams;

  out.hasRangeImage = true;
  out.rangeImage_setSize(h, w);
  const std::size_t n = frame.validCount();
  out.hasPoints3D = true;
  out.resizePoints3DVectors(n);
  std::size_t k = 0;
  for (int r = 0; r < h; r++)
    for (int c = 0; c < w; c++) {
      if (!frame.isValid(r, c)) {
        out.rangeImage(r, c) = 0;
        continue;
      }
      const double units = std::round(frame.range(r, c) / out.rangeUnits);
      out.rangeImage(r, c) = static_cast<std::uint16_t>(std::clamp(units, 1.0, 65535.0));
      const cv::Vec3f& p = frame.xyz(r, c);
      out.points3D_x[k] = p[0];
      out.points3D_y[k] = p[1];
      out.points3D_z[k] = p[2];
      out.points3D_idxs_x[k] = static_cast<std::uint16_t>(c);
      out.points3D_idxs_y[k] = static_cast<std::uint16_t>(r);
      k++;
    }

  out.hasIntensityImage = frame.has_intensity;
  if (frame.has_intensity) {
    const cv::Mat_<std::uint8_t> img8 = io::stretchToU8(frame.intensity, frame.valid);
    out.intensityImage = mrpt::img::CImage(img8, mrpt::img::DEEP_COPY);
    out.intensityImageChannel = mrpt::obs::CObservation3DRangeScan::CH_IR;
    auto& layer = out.rangeImageOtherLayers[kIntensityLayer];
    layer.setSize(h, w);
    for (int r = 0; r < h; r++)
      for (int c = 0; c < w; c++)
        layer(r, c) = static_cast<std::uint16_t>(
            std::clamp(std::round(static_cast<double>(frame.intensity(r, c))), 0.0, 65535.0));
  }
}

cv::Mat_<std::uint16_t> rangeLayer(const mrpt::obs::CObservation3DRangeScan& obs,
                                   const std::string& name) {
  const auto it = obs.rangeImageOtherLayers.find(name);
  if (it == obs.rangeImageOtherLayers.end()) return {};
  const auto& m = it->second;
  const int rows = static_cast<int>(m.rows()), cols = static_cast<int>(m.cols());
  int h = static_cast<int>(obs.rangeImage.rows()), w = static_cast<int>(obs.rangeImage.cols());
  if (!obs.hasRangeImage || h * w != rows * cols) {  // cannot tell: return as stored
    h = rows;
    w = cols;
  }
  cv::Mat_<std::uint16_t> out(h, w);
  // Row-major buffer of the stored matrix, reinterpreted with the range image's shape.
  for (int i = 0; i < rows * cols; i++) out(i / w, i % w) = m(i / cols, i % cols);
  return out;
}

}  // namespace dynobj::mrptio
