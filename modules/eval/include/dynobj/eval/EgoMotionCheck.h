// SPDX-License-Identifier: BSD-3-Clause
// The detector's ego-motion checked without ground truth: each pair of consecutive frames is also
// registered geometrically with MRPT's 3D ICP (mrpt::slam::CICP::Align3D, seeded with ICP's own
// previous motion — independent of the intensity ego-motion), and the two motions are compared.
// What `dynobj-detect --check-ego` prints and docs/accuracy.md reports for real recordings.
#pragma once

#include <dynobj/core/EgoMotionEstimator.h>
#include <dynobj/core/LidarFrame.h>

#include <memory>
#include <string>
#include <vector>

namespace dynobj::eval {

struct EgoMotionAgreement {
  int pairs = 0;                  ///< consecutive frame pairs seen
  int ego_ok = 0;                 ///< pairs whose intensity ego-motion succeeded
  int icp_ok = 0;                 ///< pairs ICP registered (goodness above its threshold)
  int compared = 0;               ///< pairs where both succeeded
  int agree = 0;                  ///< ... and differ by at most max_translation and max_rotation
  double max_translation = 0.10;  ///< [m] agreement bound used
  double max_rotation = 0.5;      ///< [deg] agreement bound used
  std::vector<double> translation_diff;  ///< [m] per compared pair
  std::vector<double> rotation_diff;     ///< [deg] per compared pair
  std::vector<double> icp_speed;         ///< [m per frame] ICP translation per registered pair

  /// "ego-motion succeeded on A of P pairs (x %); agrees with ICP on G of C (x %): translation
  /// median/p95 ..., rotation median/p95 ...".
  std::string toString() const;
};

class EgoMotionCheck {
 public:
  /// `voxel` [m]: the clouds are thinned to one point per voxel before ICP.
  explicit EgoMotionCheck(double voxel = 0.25);
  ~EgoMotionCheck();
  EgoMotionCheck(const EgoMotionCheck&) = delete;
  EgoMotionCheck& operator=(const EgoMotionCheck&) = delete;

  /// Registers `frame` against the previous one and compares with `ego` (its motion is
  /// T_{prev<-cur}, like ICP's result). The first frame only becomes the reference.
  void add(const core::LidarFrame& frame, const core::EgoMotion& ego);
  const EgoMotionAgreement& summary() const { return summary_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  EgoMotionAgreement summary_;
};

}  // namespace dynobj::eval
