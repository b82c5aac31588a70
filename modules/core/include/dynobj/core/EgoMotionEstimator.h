// SPDX-License-Identifier: BSD-3-Clause
// Paper III-B-1, Eq. (5): ego-motion between consecutive frames from ORB features of the
// intensity image, lifted to 3D through the frame's pixel -> point map, then a rigid SE(3) by
// RANSAC + closed-form least squares (Umeyama). Image preparation: see docs/algorithm.md §3
// (33 px wrap/reflect padding so ORB's 31 px border and patch fit; a mask away from no-return
// borders, where a no-return between returns above and below is filled and no border, and away
// from the last frame's dynamic objects).
#pragma once

#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <random>
#include <string>
#include <vector>

#include "dynobj/core/EgoMotion.h"
#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/MotionFromMatches.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

class EgoMotionEstimator {
 public:
  explicit EgoMotionEstimator(const EgoMotionParams& p = {});

  /// Detects ORB features on `intensity` (0..255, the normalised intensity of `frame`) away from
  /// `exclude` (may be empty), matches them with the previous frame's and estimates the motion.
  /// The first call (no previous frame) returns ok = false, source "none".
  EgoMotion estimate(const LidarFrame& frame, const cv::Mat_<float>& intensity,
                     const cv::Mat_<std::uint8_t>& exclude);

  /// Forgets previous-frame keypoints lying on `dynamic` pixels (call once the frame's dynamic
  /// mask is known, so the next estimate matches static structure only).
  void dropPreviousOn(const cv::Mat_<std::uint8_t>& dynamic);

  void reset();

 private:
  struct Features {
    std::vector<cv::Point3f> points;  ///< 3D point of each keypoint
    std::vector<int> pixels;          ///< its pixel index
    /// J_u J_u^T + J_v J_v^T: J the point's step to the next pixel on its surface across and
    /// along the scan (zero where no neighbour is on it); see EgoMotionParams::pixel_spread
    std::vector<Eigen::Matrix3d> spread;
    cv::Mat descriptors;
  };
  void detect(const LidarFrame& frame, const cv::Mat_<float>& intensity,
              const cv::Mat_<std::uint8_t>& exclude, Features& out);
  /// Ratio-test matches current -> previous; window = 0: all pairs (OpenCV brute force).
  void match(int cols, int window, std::vector<std::pair<int, int>>& out);
  /// RANSAC + least squares on the matched 3D points (Eq. 5); fills motion, inliers, ok.
  void solve(const std::vector<std::pair<int, int>>& pairs, EgoMotion& em);

  EgoMotionParams p_;
  cv::Ptr<cv::ORB> detector_;   ///< ORB keypoints (FAST, Harris, orientation)
  cv::Ptr<cv::ORB> describer_;  ///< ORB descriptors of those keypoints
  cv::BFMatcher matcher_;
  Features prev_, cur_;
  bool have_prev_ = false;
  std::mt19937 rng_;
  cv::Mat img8_, padded_, mask_, mask_pad_;
  cv::Mat_<std::uint8_t> filled_;  ///< returns, and no-returns between returns above and below
  std::vector<std::vector<int>> buckets_;
  PixelPitch pitch_;                 ///< the current sensor's
  std::vector<PointMatch> matches_;  ///< solve()'s matches (kept: no allocation per frame)
};

}  // namespace dynobj::core
