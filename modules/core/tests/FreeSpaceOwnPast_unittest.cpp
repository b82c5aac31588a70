// SPDX-License-Identifier: BSD-3-Clause
// FreeSpaceParams::exclude_own_past (docs/algorithm.md 7b): a long object that moves along itself
// by less than its length covered its own rear part in the past frame; those points are no
// evidence either way.
#include <dynobj/core/FreeSpaceCheck.h>
#include <gtest/gtest.h>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Scene;

namespace {

/// A "car" of five touching posts (x from 0 to 2.4 m, 3 m to the left of a still sensor) that
/// drove 1 m forward (+x) between frame 0 and frame 1: its rear 1.4 m is where its front was.
struct CarAlong : dynobj::test::TwoStillFrames {
  Cluster car;  ///< frame 1's points on it

  /// Five touching posts from x = `x0` - 0.3 on.
  static Scene car5(double x0) {
    Scene s;
    for (int i = 0; i < 5; i++) s.posts.push_back({x0 + 0.45 * i, 3, 0.3, 1.8});
    return s;
  }
  explicit CarAlong(const FreeSpaceParams& p = {})
      : TwoStillFrames(car5(0.3), car5(1.3), dynobj::test::smallSensor(32, 720), p) {
    for (int r = 0; r < f1.rows(); r++)
      for (int c = 0; c < f1.cols(); c++) {
        const cv::Vec3f& q = f1.xyz(r, c);
        if (f1.isValid(r, c) && std::abs(q[1] - 3) < 0.5 && q[0] < 5 && q[2] > -0.7f)
          car.pixels.push_back(r * f1.cols() + c);
      }
  }
  FreeSpaceEvidence evidence(bool own_past) const {
    return check.evidence(f1, 1, car, 0, chain, Eigen::Vector3d(1, 0, 0), {}, own_past);
  }
};

}  // namespace

TEST(FreeSpaceCheck, ALongObjectsRearWhereItsFrontWasIsNoEvidence) {
  const CarAlong t;
  ASSERT_GT(t.car.pixels.size(), 40u);
  // Every point counted: the rear was the car itself then, and outweighs the new front.
  const FreeSpaceEvidence all = t.evidence(false);
  EXPECT_GT(all.occupied, all.free);
  EXPECT_FALSE(all.provesMotion(t.check.params()));
  EXPECT_EQ(all.free + all.occupied + all.unknown, static_cast<int>(t.car.pixels.size()));
  // Its own past body left out: only the front 1 m (+ margin) is asked, and it was free then.
  const FreeSpaceEvidence front = t.evidence(true);
  EXPECT_EQ(front.occupied, 0);
  EXPECT_GE(front.free, t.check.params().min_evidence);
  EXPECT_TRUE(front.provesMotion(t.check.params(), true));  // even as a sliding cluster
  EXPECT_EQ(front.free + front.occupied + front.unknown, static_cast<int>(t.car.pixels.size()));
  // Which points are left out follows the motion's direction: read backwards (the car reversing
  // 1 m), the part left out is the other end, and the evidence differs.
  const FreeSpaceEvidence reversed =
      t.check.evidence(t.f1, 1, t.car, 0, t.chain, Eigen::Vector3d(-1, 0, 0), {}, true);
  EXPECT_GT(reversed.occupied, 0);
}

TEST(FreeSpaceCheck, ReviewLeavesOutTheOwnPastOnlyForARigidMoverAndWhenOn) {
  MovementDecision rigid;  // a rigid long object moving along itself at 1 m/s (dt 1 s)
  rigid.enough_history = rigid.candidate = rigid.rigid = rigid.slides = true;
  rigid.velocity = Eigen::Vector3d(1, 0, 0);
  FreeSpaceParams p;
  p.lookback = 1;
  p.max_lookback = 1;
  const CarAlong on(p);
  MovementDecision d = rigid;
  on.check.review(on.f1, 1, on.car, on.chain, 1.0, d);
  EXPECT_FALSE(d.static_surface);
  MovementDecision not_rigid = rigid;  // a compact or non-rigid candidate: every point counts
  not_rigid.rigid = not_rigid.slides = false;
  on.check.review(on.f1, 1, on.car, on.chain, 1.0, not_rigid);
  EXPECT_TRUE(not_rigid.static_surface);
  p.exclude_own_past = false;
  const CarAlong off(p);
  d = rigid;
  off.check.review(off.f1, 1, off.car, off.chain, 1.0, d);
  EXPECT_TRUE(d.static_surface);
}
