// SPDX-License-Identifier: BSD-3-Clause
// Beyond the paper (docs/algorithm.md §3b): the intensity ego-motion of Eq. (5) refined on the
// geometry of the range images. The feature estimate rests on ~100-200 ORB matches, each located to
// a pixel: a few tenths of a degree of rotation per frame, which the sliding window (Eq. 16)
// accumulates into apparent motion of far static structure, and a drift when the matches gather on
// one object. The refinement is a point-to-plane ICP with projective association (each sampled
// point of the current frame is carried into the previous frame by the current estimate and
// projected with Eq. 1; its partner is the previous frame's point in that pixel, with the normal of
// the previous range image there, gated on the point-to-plane distance), Huber-weighted, starting
// from the feature estimate (or from the constant-velocity guess when the features failed) and
// damped towards it. A direction of translation that few partners see (a long street's axis, where
// the only partners facing it are a few posts, car ends, and the car ahead that moves) keeps the
// feature estimate's translation (degenerate_share: solution remapping, Zhang, Kaess & Singh, ICRA
// 2016).
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <opencv2/core.hpp>
#include <optional>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/Params.h"
#include "dynobj/core/SphericalProjection.h"

namespace dynobj::core {

struct EgoRefinementParams : public StageParams {
  bool enabled = true;
  int points = 3000;          ///< pixels of the current frame sampled (evenly)
  int iterations = 8;         ///< Gauss-Newton steps at most, of which the first ...
  int coarse_iterations = 3;  ///< ... this many use every 4th sampled point (coarse to fine)
  /// [m] a partner farther than this from the other point's tangent plane is ignored (first
  /// step) ...
  double max_distance = 0.5;
  double final_distance = 0.2;  ///< [m] ... shrinking linearly to this at the last step
  /// [m] ... and one farther than this in any direction. Along its surface a partner lies up to
  /// half a pixel's footprint away, metres on the far ground of a 16-row sensor: gating that
  /// distance at final_distance kept the partners that happened to lie near a ring and tilted a
  /// VLP-16's pitch by 0.16 deg per sweep on a street (0 = gate the distance itself at
  /// max_distance ... final_distance)
  double max_offset = 1.0;
  double huber = 0.05;     ///< [m] Huber kernel width on point-to-plane residuals
  double damping = 0.001;  ///< step damping, relative to the mean information per axis
  /// [m] a normal's two neighbours in its row are at least this far apart (near the sensor the
  /// adjacent columns are millimetres apart and their range noise would tilt it at random)
  double normal_baseline = 0.1;
  /// [m] on a ground pixel whose vertical neighbours are not on its surface (the ring gap of a
  /// 16-row sensor), the normal's second direction runs between the nearest ground returns above
  /// and below in the column, when they are at most this far apart (0 = off) ...
  double ground_chain = 3.0;
  /// [m] ... and the pixel lies this close to the line between them
  double ground_flatness = 0.05;
  int min_correspondences = 300;  ///< fewer partners: the feature estimate is kept
  /// a direction of translation that fewer than this share of the partners' normals face
  /// (information along it / partners, rotation marginalised; a long street's axis: ~0.005, a
  /// hall's weakest: ~0.07) keeps the feature estimate's translation (0 = the refinement's own)
  double degenerate_share = 0.01;
  double max_correction = 0.5;  ///< [m] a larger change of translation is rejected ...
  double max_correction_angle = 3.0 * M_PI / 180.0;  ///< [rad] (INI: degrees) ... or of rotation

  void visit(ParamVisitor& v) override;
  void validate() const override;
};

struct EgoRefinement {
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  ///< T_{prev<-cur}
  bool ok = false;          ///< enough partners and a correction within bounds
  int correspondences = 0;  ///< partners at the last step
  int degenerate = 0;       ///< directions of translation left to the feature estimate
};

class EgoMotionRefiner {
 public:
  explicit EgoMotionRefiner(const EgoRefinementParams& p = {});

  /// Refines `init` (T_{prev<-cur}) between the remembered frame and `frame`. Partners on
  /// `exclude_prev` (the previous frame's dynamic pixels; may be empty) are ignored. Without a
  /// remembered frame of the same size: ok = false.
  EgoRefinement refine(const LidarFrame& frame, const Eigen::Isometry3d& init,
                       const cv::Mat_<std::uint8_t>& exclude_prev) const;
  /// Keeps `frame`'s points and its `ground` pixels (may be empty) as the previous frame of the
  /// next call (normals computed on demand).
  void remember(const LidarFrame& frame, const cv::Mat_<std::uint8_t>& ground = {});
  void reset() { have_prev_ = false; }
  const EgoRefinementParams& params() const { return p_; }

 private:
  EgoRefinementParams p_;
  bool have_prev_ = false;
  /// The previous frame's range image, points and normals: a normal is computed when a partner
  /// first needs it (prev_normal_known_ 0 = not yet; (0,0,0) = none there).
  cv::Mat_<float> prev_range_;
  cv::Mat_<std::uint8_t> prev_ground_;  ///< empty: no ground mask was given
  cv::Mat_<cv::Vec3f> prev_xyz_;
  mutable cv::Mat_<cv::Vec3f> prev_normal_;
  mutable cv::Mat_<std::uint8_t> prev_normal_known_;  ///< 1 = prev_normal_ computed there
  cv::Vec3f normalAt(int r, int c) const;
  /// Asks the memory for what a look-up at previous-frame pixel (r, c) reads (no effect on
  /// results).
  void prefetchPixel(int r, int c, const cv::Mat_<std::uint8_t>* exclude) const;
  /// Reverts the translation change of T (from init) along the directions of translation that
  /// the last step's information H (undamped, over `partners`) hardly constrains; returns them.
  int keepFeatureTranslationWhereDegenerate(const Eigen::Matrix<double, 6, 6>& H, int partners,
                                            const Eigen::Isometry3d& init,
                                            Eigen::Isometry3d& T) const;
  std::optional<SphericalProjection> proj_;  ///< Eq. (1) of the remembered frame's sensor
};

}  // namespace dynobj::core
