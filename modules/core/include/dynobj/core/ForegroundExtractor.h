// SPDX-License-Identifier: BSD-3-Clause
// Paper III-A-2, Eq. (2)-(4): foreground feature pixels of the intensity image.
//   h = f * g   with a flat (2a+1) x (2b+1) Gaussian kernel, sigma_m (horizontal), sigma_n
//   t = B(f - h, theta)
// f is the frame's intensity after a per-frame percentile stretch to 0..255 (works for Ouster
// signal, Velodyne 0-255 and simulated units alike); the range image when there is no intensity.
#pragma once

#include <opencv2/core.hpp>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

struct ForegroundParams : public StageParams {
  int kernel_half_width = 7;      ///< a [px]: kernel is 2a+1 columns wide (a > b: flat kernel)
  int kernel_half_height = 1;     ///< b [px]: kernel is 2b+1 rows high
  double sigma_horizontal = 3.5;  ///< sigma_m [px]
  double sigma_vertical = 1.0;    ///< sigma_n [px]
  double threshold = 14.0;        ///< theta [stretched intensity units, 0..255]
  bool absolute = true;  ///< |f - h| > theta (darker objects too); false = paper's f - h > theta
  double stretch_low = 1.0;    ///< percentile mapped to 32 (of 0..255)
  double stretch_high = 99.0;  ///< percentile mapped to 223
  bool exclude_ground = true;  ///< no features on ground pixels (the detector applies it)

  void visit(ParamVisitor& v) override;
  void validate() const override;
};

class ForegroundExtractor {
 public:
  explicit ForegroundExtractor(const ForegroundParams& p = {});

  /// Normalised intensity f (CV_32F, 0..255: percentiles stretch_low/high -> 32/223, clamped;
  /// 0 where no return), reused by the ego-motion stage.
  const cv::Mat_<float>& normalize(const LidarFrame& frame);
  /// Eq. (4): `features` = 255 where t(u, v) = 1 among valid pixels not in `exclude` (may be
  /// empty). Calls normalize() first. The blur is normalised by the valid mask, so no-return
  /// pixels neither count as dark background nor create features at their borders.
  void extract(const LidarFrame& frame, const cv::Mat_<std::uint8_t>& exclude,
               cv::Mat_<std::uint8_t>& features);
  /// extract() on the image of the last normalize(frame), which it only reads (the ego-motion
  /// may read it at the same time).
  void extractNormalized(const LidarFrame& frame, const cv::Mat_<std::uint8_t>& exclude,
                         cv::Mat_<std::uint8_t>& features);

  /// The last normalised intensity (after extract() or normalize()).
  const cv::Mat_<float>& normalized() const { return f_; }
  const ForegroundParams& params() const { return p_; }

 private:
  ForegroundParams p_;
  cv::Mat_<float> f_, v_, blurred_, weight_;
  cv::Mat vert_, padded_, scratch_;  ///< blur buffers, kept across frames
  std::vector<float> sample_, bin_;
  std::vector<std::uint32_t> hist_;  ///< samples per top 12 bits of their order key
};

}  // namespace dynobj::core
