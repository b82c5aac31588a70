// SPDX-License-Identifier: BSD-3-Clause
// A label-free check of a detector's output on a user's own recording (issue #17, item 5): a
// flagged point is *suspicious* when the other sweeps that look at its place (within
// `neighbours` sweeps, through the detector's own ego-motion) mostly see a surface there — a
// static thing flagged — and *transient* when they mostly see through it — it was there only
// for a moment, as movers are. A sample of the unflagged points is classified the same way: the
// transient ones among them estimate what was missed. Porous things (foliage) and the limits of
// the pixel grid make both classes approximate; the figures compare detector versions on the
// same recording, they are not precision or recall.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/SphericalProjection.h"

namespace dynobj::eval {

struct ConsistencyParams {
  double max_range = 45.0;     ///< [m] points and views farther than this are not used
  int neighbours = 30;         ///< sweeps each side that are asked about a point
  double margin = 0.25;        ///< [m] a view's range agrees within margin + range_factor x range
  double range_factor = 0.01;  ///< [-]
  int min_views = 4;           ///< fewer decisive views: the point is "unknown"
  double static_share = 0.6;   ///< occupied / decisive views at least this: static
  double transient_share = 0.25;  ///< occupied / decisive views at most this: transient
  int unflagged_sample = 50;      ///< every n-th unflagged point is classified (seeded)
};

struct ConsistencyReport {
  long sweeps = 0, points = 0;
  long flagged = 0, flagged_static = 0, flagged_transient = 0, flagged_unknown = 0;
  long unflagged_sampled = 0, unflagged_transient = 0, unflagged_sample_step = 1;

  double flaggedShare() const;     ///< flagged / points
  double suspiciousShare() const;  ///< flagged_static / flagged
  double transientShare() const;   ///< flagged_transient / flagged
  /// Unflagged points estimated transient (sample count x step): what may have been missed.
  long missedEstimate() const { return unflagged_transient * unflagged_sample_step; }
  std::string toString() const;
};

class MapConsistency {
 public:
  explicit MapConsistency(const ConsistencyParams& p = {});

  /// One sweep: its frame, the sensor pose in the sequence's frame (accumulated ego-motion) and
  /// the detector's dynamic mask (H x W, non-zero = flagged). Keeps the range image and the
  /// points within max_range (memory grows with the sequence: an offline check).
  void add(const core::LidarFrame& frame, const Eigen::Isometry3d& pose,
           const cv::Mat_<std::uint8_t>& dynamic);

  ConsistencyReport evaluate();
  /// Top view [BGR, `resolution` m/px] of the classified points after evaluate(): static map
  /// grey, flagged transient red, flagged static yellow, flagged unknown magenta, unflagged
  /// transient green, the sensor path cyan.
  cv::Mat topView(double resolution = 0.1) const;

 private:
  enum Class : std::uint8_t { kUnknown, kStatic, kTransient, kBetween };
  Class classify(const Eigen::Vector3f& world, std::size_t own) const;

  struct Sweep {
    Eigen::Isometry3d pose;
    Eigen::Isometry3d sensor_from_world;  ///< pose.inverse(), asked once per point and view
    cv::Mat_<float> range;
    std::vector<Eigen::Vector3f> points;  ///< world frame
    std::vector<std::uint8_t> flagged;
  };
  ConsistencyParams p_;
  std::optional<core::SphericalProjection> proj_;  ///< Eq. (1) of the first sweep's sensor
  std::vector<Sweep> sweeps_;
  std::vector<std::pair<Eigen::Vector3f, std::uint8_t>> marks_;  ///< point, colour index
};

}  // namespace dynobj::eval
