// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/EgoMotionError.h>
#include <gtest/gtest.h>

using dynobj::eval::EgoMotionError;

TEST(EgoMotionError, RmsAndMaximumOfHandMadePairs) {
  EgoMotionError e;
  EXPECT_EQ(e.rmsTranslation(), 0.0);  // nothing yet
  Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();
  truth.translation() = Eigen::Vector3d(1, 0, 0);
  Eigen::Isometry3d est = truth;
  est.translation() += Eigen::Vector3d(0, 0.03, 0.04);  // 5 cm off
  e.add(truth, est);
  Eigen::Isometry3d turned = truth * Eigen::AngleAxisd(2.0 * M_PI / 180, Eigen::Vector3d::UnitZ());
  e.add(truth, turned);  // 2 degrees off, no translation error
  EXPECT_EQ(e.pairs(), 2u);
  EXPECT_NEAR(e.rmsTranslation(), std::sqrt(0.05 * 0.05 / 2), 1e-12);
  EXPECT_NEAR(e.maxTranslation(), 0.05, 1e-12);
  EXPECT_NEAR(e.rmsRotation(), std::sqrt(4.0 / 2), 1e-9);
  EXPECT_NEAR(e.maxRotation(), 2.0, 1e-9);
  EXPECT_EQ(e.toString(),
            "ego-motion error over 2 pairs: translation RMS 0.035 m (max 0.050), rotation RMS "
            "1.414 deg (max 2.000)");
}
