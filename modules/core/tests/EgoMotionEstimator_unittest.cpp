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
