// SPDX-License-Identifier: BSD-3-Clause
// Ground pixels of the range image, so that region growing (Eq. 24-25) never spreads into the
// floor. Per column, from the lowest beam up: the first return is ground when it lies near the
// frame's ground height; each next return stays ground while the slope from the last ground
// return is below max_slope. (The paper uses "ground plane information" without saying how.)
#pragma once

#include <opencv2/core.hpp>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

struct GroundParams : public StageParams {
  double max_slope = 10.0 * M_PI / 180;  ///< [rad; deg in INI] steepest slope still ground
  double height_tolerance = 0.25;  ///< [m] first return of a column: |z - ground z| below this
  double max_step = 0.08;          ///< [m] a quarter of it is the noise allowance of the slope test

  void visit(ParamVisitor& v) override;
};

class GroundSegmenter {
 public:
  explicit GroundSegmenter(const GroundParams& p = {});
  /// `ground` = 255 on ground pixels. Returns the estimated ground height (sensor frame z [m]).
  double segment(const LidarFrame& frame, cv::Mat_<std::uint8_t>& ground);

 private:
  GroundParams p_;
  std::vector<float> zs_;
  std::vector<std::uint8_t> have_last_;   ///< per column: the ground chain has started
  std::vector<double> last_xy_, last_z_;  ///< per column: its last ground return
};

}  // namespace dynobj::core
