// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/ObservationTagging.h"

#include <mrpt/obs/TPixelLabelInfo.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "dynobj/mrptio/ObservationConverter.h"
#include "dynobj/mrptio/RangeScanLayout.h"

namespace dynobj::mrptio {
namespace {

using mrpt::obs::CObservation3DRangeScan;

[[noreturn]] void fail(const CObservation3DRangeScan& o, const std::string& what) {
  throw ConversionError("CObservation3DRangeScan '" + o.sensorLabel + "': " + what);
}

void requireLayout(const CObservation3DRangeScan& o, const cv::Mat_<std::uint8_t>* mask) {
  if (!o.hasRangeImage || o.rangeImage.rows() == 0)
    fail(o, "has no range image (not in the organized LiDAR layout)");
  const std::size_t n = o.points3D_x.size();
  if (o.hasPoints3D && (o.points3D_y.size() != n || o.points3D_z.size() != n ||
                        o.points3D_idxs_x.size() != n || o.points3D_idxs_y.size() != n))
    fail(o, "points3D_* and points3D_idxs_* have different lengths");
  if (mask && (mask->rows != o.rangeImage.rows() || mask->cols != o.rangeImage.cols()))
    fail(o, "mask is " + std::to_string(mask->rows) + "x" + std::to_string(mask->cols) +
                " but the scan is " + std::to_string(o.rangeImage.rows()) + "x" +
                std::to_string(o.rangeImage.cols()));
}

/// The label index named "dynamic", creating labels / the name as needed.
int dynamicLabelIndex(CObservation3DRangeScan& o) {
  const int H = static_cast<int>(o.rangeImage.rows()), W = static_cast<int>(o.rangeImage.cols());
  if (!o.pixelLabels) {
    o.pixelLabels = std::make_shared<mrpt::obs::TPixelLabelInfo<1>>();
    o.pixelLabels->setSize(H, W);
  }
  const int existing = o.pixelLabels->checkLabelNameExistence(kDynamicLabel);
  if (existing >= 0) return existing;
  const int bits = 8 * o.pixelLabels->BITFIELD_BYTES;
  for (int i = 0; i < bits; i++)
    if (!o.pixelLabels->pixelLabelNames.count(static_cast<std::uint32_t>(i))) {
      o.pixelLabels->setLabelName(static_cast<unsigned>(i), kDynamicLabel);
      return i;
    }
  fail(o, "all " + std::to_string(bits) + " pixel label bits are taken; no room for '" +
              kDynamicLabel + "'");
}

}  // namespace

TagStats markDynamic(CObservation3DRangeScan& o, const cv::Mat_<std::uint8_t>& mask) {
  requireLayout(o, &mask);
  const int idx = dynamicLabelIndex(o);
  TagStats st;
  for (int r = 0; r < mask.rows; r++)
    for (int c = 0; c < mask.cols; c++) {
      if (mask(r, c)) {
        o.pixelLabels->setLabel(r, c, static_cast<std::uint8_t>(idx));
        st.pixels += o.rangeImage(r, c) != 0;
      } else {
        o.pixelLabels->unsetLabel(r, c, static_cast<std::uint8_t>(idx));
      }
    }
  return st;
}

TagStats dropDynamic(CObservation3DRangeScan& o, const cv::Mat_<std::uint8_t>& mask) {
  TagStats st = markDynamic(o, mask);
  const int H = mask.rows, W = mask.cols;
  cv::Mat_<std::uint16_t> kept = rangeLayer(o, kDynamicLayer);  // earlier drops, H x W
  auto& layer = o.rangeImageOtherLayers[kDynamicLayer];
  layer.setSize(H, W);
  for (int r = 0; r < H; r++)
    for (int c = 0; c < W; c++) {
      layer(r, c) = kept.empty() ? 0 : kept(r, c);
      if (mask(r, c) && o.rangeImage(r, c) != 0) {
        layer(r, c) = o.rangeImage(r, c);
        o.rangeImage(r, c) = 0;
      }
    }
  std::size_t w = 0;  // compact the five point vectors in place
  for (std::size_t i = 0; i < o.points3D_x.size(); i++) {
    if (mask(o.points3D_idxs_y[i], o.points3D_idxs_x[i])) {
      st.points_removed++;
      continue;
    }
    o.points3D_x[w] = o.points3D_x[i];
    o.points3D_y[w] = o.points3D_y[i];
    o.points3D_z[w] = o.points3D_z[i];
    o.points3D_idxs_x[w] = o.points3D_idxs_x[i];
    o.points3D_idxs_y[w] = o.points3D_idxs_y[i];
    w++;
  }
  o.resizePoints3DVectors(w);
  return st;
}

TagStats restoreDynamic(CObservation3DRangeScan& o) {
  requireLayout(o, nullptr);
  TagStats st;
  const cv::Mat_<std::uint16_t> layer = rangeLayer(o, kDynamicLayer);
  if (layer.empty()) return st;  // nothing was dropped
  const int H = static_cast<int>(o.rangeImage.rows()), W = static_cast<int>(o.rangeImage.cols());
  // Each row's elevation from its remaining points (median), to put the restored points on it.
  std::vector<std::vector<double>> el(static_cast<std::size_t>(H));
  for (std::size_t i = 0; i < o.points3D_x.size(); i++) {
    const double x = o.points3D_x[i], y = o.points3D_y[i], z = o.points3D_z[i];
    const double rr = std::sqrt(x * x + y * y + z * z);
    if (rr > 0) el[o.points3D_idxs_y[i]].push_back(std::asin(z / rr));
  }
  std::vector<double> row_el(static_cast<std::size_t>(H), std::nan(""));
  for (int r = 0; r < H; r++) {
    auto& v = el[static_cast<std::size_t>(r)];
    if (v.empty()) continue;
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    row_el[static_cast<std::size_t>(r)] = v[v.size() / 2];
  }
  for (int r = 0; r < H; r++)
    for (int c = 0; c < W; c++) {
      const std::uint16_t raw = layer(r, c);
      if (!raw) continue;
      o.rangeImage(r, c) = raw;
      double e = row_el[static_cast<std::size_t>(r)];
      if (std::isnan(e)) {  // a row with no other point: interpolate between the nearest ones
        int a = r - 1, b = r + 1;
        while (a >= 0 && std::isnan(row_el[static_cast<std::size_t>(a)])) a--;
        while (b < H && std::isnan(row_el[static_cast<std::size_t>(b)])) b++;
        if (a < 0 && b >= H)
          fail(o, "cannot restore: no remaining point tells the beam elevations");
        e = a < 0 ? row_el[static_cast<std::size_t>(b)]
                  : (b >= H ? row_el[static_cast<std::size_t>(a)]
                            : row_el[static_cast<std::size_t>(a)] +
                                  (row_el[static_cast<std::size_t>(b)] -
                                   row_el[static_cast<std::size_t>(a)]) *
                                      (r - a) / (b - a));
      }
      const double az = -M_PI + (c + 0.5) * 2 * M_PI / W;  // Eq. (1) column centre
      const double d = raw * static_cast<double>(o.rangeUnits);
      o.points3D_x.push_back(static_cast<float>(d * std::cos(e) * std::cos(az)));
      o.points3D_y.push_back(static_cast<float>(d * std::cos(e) * std::sin(az)));
      o.points3D_z.push_back(static_cast<float>(d * std::sin(e)));
      o.points3D_idxs_x.push_back(static_cast<std::uint16_t>(c));
      o.points3D_idxs_y.push_back(static_cast<std::uint16_t>(r));
      st.points_restored++;
      st.pixels++;
    }
  o.hasPoints3D = true;
  o.rangeImageOtherLayers.erase(kDynamicLayer);
  return st;
}

}  // namespace dynobj::mrptio
