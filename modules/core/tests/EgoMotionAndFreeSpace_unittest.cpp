// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/EgoMotionEstimator.h>
#include <dynobj/core/ForegroundExtractor.h>
#include <dynobj/core/FreeSpaceCheck.h>
#include <gtest/gtest.h>

#include <random>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Scene;

TEST(EgoMotionEstimator, RecoversAKnownRigidMotion) {
  const auto s = dynobj::test::smallSensor(64, 1024);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 3; trial++) {
    Scene a;
    a.posts = {{3, 2, 0.4, 2.0}, {-4, 1, 0.3, 2.5}, {1, -5, 0.5, 1.5}};
    Scene b = a;  // the sensor moved: T_{a<-b}
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.3 * u(rng), 0.3 * u(rng), 0.03 * u(rng));
    T.linear() = Eigen::AngleAxisd(0.06 * u(rng), Eigen::Vector3d::UnitZ()).toRotationMatrix() *
                 Eigen::AngleAxisd(0.02 * u(rng), Eigen::Vector3d::UnitX()).toRotationMatrix();
    b.sensor = T;
    const LidarFrame fa = dynobj::test::render(a, s, false, 1);
    const LidarFrame fb = dynobj::test::render(b, s, false, 2);
    ForegroundExtractor fx;
    EgoMotionEstimator ego;
    EXPECT_FALSE(ego.estimate(fa, fx.normalize(fa), {}).ok);  // no previous frame yet
    const EgoMotion em = ego.estimate(fb, fx.normalize(fb), {});
    ASSERT_TRUE(em.ok) << "trial " << trial << ": " << em.inliers << "/" << em.matches;
    EXPECT_EQ(em.source, "intensity");
    const Eigen::Isometry3d err = T.inverse() * em.motion;
    EXPECT_LT(err.translation().norm(), 0.03) << "trial " << trial;
    EXPECT_LT(Eigen::AngleAxisd(err.linear()).angle(), 0.005) << "trial " << trial;
  }
}

TEST(EgoMotionEstimator, FeaturelessScenesFailCleanly) {
  const auto s = dynobj::test::smallSensor(64, 1024);
  const LidarFrame f = dynobj::test::render(Scene{}, s, true);  // flat intensities: no corners
  ForegroundExtractor fx;
  EgoMotionEstimator ego;
  ego.estimate(f, fx.normalize(f), {});
  const EgoMotion em = ego.estimate(f, fx.normalize(f), {});
  EXPECT_FALSE(em.ok);
  EXPECT_LT(em.inliers, EgoMotionParams().min_inliers);
}

namespace {

/// Two frames of a still sensor (the scene before and after), remembered and chained, and the
/// points of the current frame within 0.35 m of a post's axis: a post's cluster.
struct TwoFrames {
  LidarFrame f0, f1;
  FrameChain chain;
  FreeSpaceCheck check;
  TwoFrames(const Scene& before, const Scene& after) {
    const auto s = dynobj::test::smallSensor(32, 512);
    f0 = dynobj::test::render(before, s, true, 1);
    f1 = dynobj::test::render(after, s, true, 2);
    chain.push(0, Eigen::Isometry3d::Identity(), true);
    chain.push(1, Eigen::Isometry3d::Identity(), true);
    check.remember(0, f0);
  }
  Cluster clusterAt(double x, double y) const {
    Cluster c;
    for (int r = 0; r < f1.rows(); r++)
      for (int col = 0; col < f1.cols(); col++) {
        const cv::Vec3f& p = f1.xyz(r, col);
        if (f1.isValid(r, col) && std::hypot(p[0] - x, p[1] - y) < 0.35 && p[2] > -0.7f)
          c.pixels.push_back(r * f1.cols() + col);
      }
    return c;
  }
};

}  // namespace

TEST(FreeSpaceCheck, MovedInVersusAlreadyThere) {
  Scene before, after;
  before.posts = {{5, 0, 0.3, 1.8}};                   // a post that stays
  after.posts = {{5, 0, 0.3, 1.8}, {4, 3, 0.3, 1.8}};  // and one that arrived at (4, 3)
  const TwoFrames t(before, after);
  const LidarFrame& f1 = t.f1;
  const FrameChain& chain = t.chain;
  const FreeSpaceCheck& check = t.check;
  const auto arrived = check.evidence(f1, 1, t.clusterAt(4, 3), 0, chain);
  const auto stayed = check.evidence(f1, 1, t.clusterAt(5, 0), 0, chain);
  EXPECT_GT(arrived.free, 5);
  EXPECT_EQ(arrived.occupied, 0);
  EXPECT_TRUE(arrived.supportsMotion(check.params()));
  EXPECT_GT(stayed.occupied, 5);
  EXPECT_EQ(stayed.free, 0);
  EXPECT_FALSE(stayed.supportsMotion(check.params()));
  // Unknown past frame: no verdict, the candidate is kept.
  EXPECT_TRUE(check.evidence(f1, 1, t.clusterAt(5, 0), 7, chain).supportsMotion(check.params()));
}

TEST(FreeSpaceCheck, ObjectMovingAwayProvesMotionByTheSpaceItLeft) {
  // A post 4 m ahead moves 1 m straight away from the sensor. In the old frame, the space it
  // occupies now was hidden behind it (no verdict); now, the space it left is seen through.
  Scene before, after;
  before.posts = {{4, 0, 0.3, 1.8}};
  after.posts = {{5, 0, 0.3, 1.8}};
  const TwoFrames t(before, after);
  const LidarFrame& f1 = t.f1;
  const FrameChain& chain = t.chain;
  const FreeSpaceCheck& check = t.check;
  const Cluster c = t.clusterAt(5, 0);
  ASSERT_GT(c.pixels.size(), 5u);
  const auto hidden = check.evidence(f1, 1, c, 0, chain);
  EXPECT_EQ(hidden.free + hidden.occupied, 0);  // hidden then: no verdict either way
  EXPECT_FALSE(hidden.provesMotion(check.params()));
  const auto left = check.evidence(f1, 1, c, 0, chain, Eigen::Vector3d(1, 0, 0));
  EXPECT_GE(left.free, static_cast<int>(c.pixels.size()) / 2);
  EXPECT_EQ(left.occupied, 0);
  EXPECT_TRUE(left.provesMotion(check.params()));
  // A post that did not move: the space "left" behind it is the post itself, still occupied.
  const auto stayed = check.evidence(f1, 1, c, 0, chain, Eigen::Vector3d(0.05, 0, 0));
  EXPECT_FALSE(stayed.provesMotion(check.params()));
}
