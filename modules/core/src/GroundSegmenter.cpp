// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/GroundSegmenter.h"

#include <algorithm>
#include <cmath>

#include "dynobj/core/Config.h"

namespace dynobj::core {

void GroundParams::visit(ParamVisitor& v) {
  v.degrees("max_slope", max_slope, {0, M_PI / 2});
  v.value("height_tolerance", height_tolerance, kPositive);
  v.value("max_step", max_step, {0, 1});
}

GroundSegmenter::GroundSegmenter(const GroundParams& p) : p_(p) {
  p_.validate();
}

double GroundSegmenter::segment(const LidarFrame& f, cv::Mat_<std::uint8_t>& ground) {
  ground.create(f.range.size());
  ground.setTo(0);
  const int H = f.rows(), W = f.cols();
  // Ground height: a low percentile of the z of the lowest returns of each column (below the
  // horizon), robust to objects standing close to the sensor.
  zs_.clear();
  for (int c = 0; c < W; c++)
    for (int r = H - 1; r >= 0; r--)
      if (f.isValid(r, c)) {
        if (f.xyz(r, c)[2] < 0) zs_.push_back(f.xyz(r, c)[2]);
        break;
      }
  if (zs_.empty()) return 0.0;
  const auto k = zs_.size() / 5;
  std::nth_element(zs_.begin(), zs_.begin() + static_cast<std::ptrdiff_t>(k), zs_.end());
  const double z_ground = zs_[k];
  const double tan_slope = std::tan(p_.max_slope);

  // Bottom-up, one column at a time (walked row by row, for the cache): the first return near the
  // ground height starts the column's ground chain; each next return is ground when it continues
  // the chain (small step, or a gentle slope away from the sensor). Objects break the chain only
  // locally: the floor seen behind a person is ground.
  have_last_.assign(static_cast<std::size_t>(W), 0);
  last_xy_.resize(static_cast<std::size_t>(W));
  last_z_.resize(static_cast<std::size_t>(W));
  const auto horizontal = [](const cv::Vec3f& p) { return std::sqrt(p[0] * p[0] + p[1] * p[1]); };
  // Everything the loop reads through locals: its byte stores could alias any member.
  const double tolerance = p_.height_tolerance, step = p_.max_step, noise = 0.25 * p_.max_step;
  std::uint8_t* have_last = have_last_.data();
  double* last_xy = last_xy_.data();
  double* last_z = last_z_.data();
  for (int r = H - 1; r >= 0; r--) {
    const std::uint8_t* valid = f.valid.ptr<std::uint8_t>(r);
    const cv::Vec3f* xyz = f.xyz.ptr<cv::Vec3f>(r);
    std::uint8_t* out = ground.ptr<std::uint8_t>(r);
    for (int c = 0; c < W; c++) {
      if (!valid[c]) continue;
      const cv::Vec3f& p = xyz[c];
      const double xy = horizontal(p);
      bool is_ground = false;
      if (!have_last[c]) {
        is_ground = std::abs(p[2] - z_ground) <= tolerance;
      } else {
        // The chain must move away from the sensor: a rise of at most max_slope over the
        // horizontal progress, plus a quarter of max_step for range noise. (A vertical surface
        // seen at close range, rows a few cm apart, must not climb as "small steps".)
        const double dxy = xy - last_xy[c], dz = std::abs(p[2] - last_z[c]);
        is_ground = dxy > -noise && dz <= tan_slope * std::max(dxy, 0.0) + noise;
      }
      if (!is_ground) continue;
      // The base of a vertical structure (a foot, a wheel, the bottom of a wall) is at ground
      // height too, but the next return above it stands at the same distance: not ground.
      int ra = r - 1;
      while (ra >= 0 && !f.valid(ra, c)) ra--;
      if (ra >= 0) {
        const cv::Vec3f& q = f.xyz(ra, c);
        if (p[2] - z_ground > step / 2 && q[2] - p[2] > step &&
            std::abs(horizontal(q) - xy) < step * 2)  // the square root last
          continue;
      }
      out[c] = 255;
      last_xy[c] = xy;
      last_z[c] = p[2];
      have_last[c] = 1;
    }
  }
  return z_ground;
}

}  // namespace dynobj::core
