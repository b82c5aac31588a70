// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/EgoMotionEstimator.h>
#include <dynobj/core/ForegroundExtractor.h>
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

// Runs of no-returns along the rows (as real sensors lose dark or shiny patches): a no-return
// between returns above and below is not a border, so the keypoints stay about as many.
TEST(EgoMotionEstimator, RunsOfNoReturnsDoNotEmptyTheKeypointMask) {
  const auto s = dynobj::test::smallSensor(64, 1024);
  Scene a;
  a.posts = {{3, 2, 0.4, 2.0}, {-4, 1, 0.3, 2.5}, {1, -5, 0.5, 1.5}};
  Scene b = a;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(0.2, -0.1, 0.0);
  b.sensor = T;
  auto holes = [](LidarFrame f, unsigned seed) {  // 5 % of the pixels, runs of 4 along a row
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> row(0, f.rows() - 1), col(0, f.cols() - 5);
    for (int k = 0; k < f.rows() * f.cols() / 80; k++) {
      const int r = row(rng), c0 = col(rng);
      for (int c = c0; c < c0 + 4; c++) {
        f.valid(r, c) = 0;
        f.range(r, c) = 0;
        f.intensity(r, c) = 0;
        f.xyz(r, c) = cv::Vec3f(0, 0, 0);
      }
    }
    return f;
  };
  const LidarFrame fa = dynobj::test::render(a, s, false, 1);
  const LidarFrame fb = dynobj::test::render(b, s, false, 2);
  auto run = [&](const LidarFrame& x, const LidarFrame& y) {
    ForegroundExtractor fx;
    EgoMotionEstimator ego;
    ego.estimate(x, fx.normalize(x), {});
    return ego.estimate(y, fx.normalize(y), {});
  };
  const EgoMotion clean = run(fa, fb), holed = run(holes(fa, 3), holes(fb, 4));
  ASSERT_TRUE(clean.ok);
  ASSERT_TRUE(holed.ok) << holed.inliers << "/" << holed.matches;
  EXPECT_GT(holed.inliers, 0.6 * clean.inliers) << holed.inliers << " vs " << clean.inliers;
  const Eigen::Isometry3d err = T.inverse() * holed.motion;
  EXPECT_LT(err.translation().norm(), 0.03);
}
