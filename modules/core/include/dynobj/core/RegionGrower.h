// SPDX-License-Identifier: BSD-3-Clause
// Paper III-C-3, Eq. (24)-(25): from the seed pixels of each dynamic object, add 8-neighbours
// (Eq. 24) of the range image whose 3D point lies within epsilon of an object point (Eq. 25; here
// epsilon grows with the angular gap between the two rays at that range, and a depth jump along
// the ray also stops the growth),
// never entering ground pixels, until nothing is added. The image wraps around horizontally.
#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/Params.h"

namespace dynobj::core {

struct RegionGrowingParams : public StageParams {
  double distance = 0.25;  ///< epsilon [m] between neighbouring points of one object
  double range_factor =
      1.2;  ///< epsilon = distance + range_factor x (gap between the rays at that range)
  double depth_factor =
      0.02;  ///< and neighbours' ranges differ by at most distance + depth_factor x range
  /// ... except that, where rows are too far apart for that, the pixel just above may lie up to
  /// slope_factor x (the gap between the two rows at that range) farther [-], when the two points
  /// are no farther apart across the rays than epsilon: an object's top set back from its face (a
  /// car's cabin behind its boot, seen from behind; its windscreen behind its bonnet) where a
  /// sparse sensor's rows jump over the surface between them. 0 = off
  double slope_factor = 3;
  /// [m] ... for objects whose seeds lie farther than this from their centre (horizontally):
  /// wider than a person, whose pixel above the head is whatever stands behind it
  double set_back_radius = 0.3;
  double max_extent = 1.5;  ///< [m] no pixel farther than this (horizontally) from the seeds'
                            ///< centre, or than the seeds' own radius plus half this, if larger
  int max_pixels = 20000;   ///< safety limit per object
  /// a mover's region does not take the points of an object whose track is at rest (judged
  /// static settled_frames ([tracking]) times in a row, or clearly stopped, stop_at_rest): a
  /// walker passing someone who stands
  bool keep_out_settled = true;
  /// [m] ... nor a point nearer to such an object's feature points than to the mover's own seeds,
  /// both within this distance: the body of one who stands beside a walker, of which the feature
  /// points alone are kept out (0 = off)
  double nearer_rest_radius = 0.5;
  /// a mover's region does not take a point that the free-space check's lookback frame saw on
  /// a surface, when the mover has since travelled farther than its own extent (so it was not
  /// there itself): a crate, a pillar or a parked car it touches. Beyond the paper (§8)
  bool past_surface_check = true;

  void visit(ParamVisitor& v) override;

  /// Eq. (25) as read here: do the points p and q (ranges rp, rq) of two neighbouring pixels
  /// whose rays are `gap` [rad] apart lie on one object? `q_above`: q's pixel is the one just
  /// above p's, in the same column.
  bool joins(const cv::Vec3f& p, double rp, const cv::Vec3f& q, double rq, double gap,
             bool q_above) const;
};

class RegionGrower {
 public:
  explicit RegionGrower(const RegionGrowingParams& p = {});
  const RegionGrowingParams& params() const { return p_; }

  static constexpr int kFree = -1;     ///< `owner` of a pixel no object has taken
  static constexpr int kKeptOut = -2;  ///< `owner` of a pixel no object may take (keepOut)

  /// Grows every object's seeds (pixel indices row * W + col) over `frame`, skipping `ground`
  /// pixels. Adds the grown pixels to `mask` (255); `owner` (CV_32S, kFree = none) tells which
  /// object (index into `seeds`) took each pixel; only kFree pixels are taken, so pixels taken
  /// by an earlier call or kept out stay theirs. `admit` (optional), asked of each pixel a
  /// region would take beyond its seeds (object index, pixel index): false keeps the pixel out
  /// of every region (owner kKeptOut). Returns the pixel count of each object.
  using Admit = std::function<bool(std::size_t, int)>;
  std::vector<int> grow(const LidarFrame& frame, const cv::Mat_<std::uint8_t>& ground,
                        const std::vector<std::vector<int>>& seeds, cv::Mat_<std::uint8_t>& mask,
                        cv::Mat_<int>& owner, const Admit& admit = {});

  /// Marks `pixels` (row * W + col) of a sized `owner` kept out of the next grow(): the points
  /// of an object known to stand still, which a mover beside it must not take.
  static void keepOut(const std::vector<int>& pixels, cv::Mat_<int>& owner);

  /// An `admit` for grow(): refuses, for object i, a pixel whose point lies nearer to one of the
  /// points of `others[i]` (pixel indices: the feature points of objects at rest beside it) than
  /// to every one of its own `seeds[i]`, both within `radius` [m]; and whatever `then` refuses.
  /// Returns `then` when no object has others.
  static Admit nearerOwnSeeds(const LidarFrame& frame, const std::vector<std::vector<int>>& seeds,
                              const std::vector<std::vector<int>>& others, double radius,
                              Admit then);

  /// The pixels the last grow() kept out because `admit` refused them.
  const std::vector<int>& refused() const { return refused_; }

 private:
  RegionGrowingParams p_;
  std::vector<int> queue_;
  std::vector<int> refused_;
};

}  // namespace dynobj::core
