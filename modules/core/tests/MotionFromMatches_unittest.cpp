// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/core/EgoMotionEstimator.h>
#include <dynobj/core/MotionFromMatches.h>
#include <gtest/gtest.h>

#include <random>

using namespace dynobj::core;

namespace {

constexpr double kColumn = 2 * M_PI / 512;  // a 512-column sensor ...
constexpr double kRow = M_PI / 2 / 63;      // ... with 64 rows over 90 degrees

/// A street seen by a sensor that drove along it (T_{prev<-cur}): 60 matches of points 4-15 m away
/// that moved with the scene, and corners that stayed in their pixels (where a line along the
/// street crosses a scan column or ring: the same point in both frames): 40 on the facades at
/// y = +-13 m, 20-60 m ahead or behind, and 40 on lane markings on the ground at y = +-5 m, 6-14 m
/// ahead or behind, 1.8 m below the sensor. Their pixel spread: the steps to the next column and
/// the next row on their surface, in both frames.
std::vector<PointMatch> streetMatches(const Eigen::Isometry3d& motion) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<PointMatch> m;
  for (int i = 0; i < 60; i++) {
    const double a = 2 * M_PI * u(rng), r = 4 + 11 * u(rng);
    PointMatch pm;
    pm.cur = {r * std::cos(a), r * std::sin(a), -1.5 + 3 * u(rng)};
    pm.prev = motion * pm.cur;
    m.push_back(pm);
  }
  for (int i = 0; i < 40; i++) {
    const double x = (i % 2 ? 1 : -1) * (20 + 40 * u(rng)), y = i % 4 < 2 ? 13 : -13;
    PointMatch pm;
    pm.cur = pm.prev = {x, y, 8 * u(rng)};
    const double r = pm.cur.head<2>().norm(), grazing = std::abs(y) / r;  // sine of the angle
    const Eigen::Vector3d step = Eigen::Vector3d::UnitX() * (r * kColumn / grazing);
    pm.spread = 2 * step * step.transpose();
    pm.still = true;
    m.push_back(pm);
  }
  for (int i = 0; i < 40; i++) {
    const double x = (i % 2 ? 1 : -1) * (6 + 8 * u(rng)), y = i % 4 < 2 ? 5 : -5, h = 1.8;
    PointMatch pm;
    pm.cur = pm.prev = {x, y, -h};
    pm.still = true;
    const double r = std::hypot(x, y);
    const Eigen::Vector3d across = Eigen::Vector3d(-y, x, 0) * kColumn;  // r kColumn, tangential
    const Eigen::Vector3d along = Eigen::Vector3d(x, y, 0) * (r * kRow / h);  // r^2 kRow / h
    pm.spread = 2 * (across * across.transpose() + along * along.transpose());
    m.push_back(pm);
  }
  return m;
}

Eigen::Isometry3d forward(double x) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = x;
  return T;
}

}  // namespace

TEST(MotionFromMatches, CornersThatStayInTheirPixelsDoNotHoldBackTheMotion) {
  const Eigen::Isometry3d truth = forward(0.5);
  const auto matches = streetMatches(truth);
  auto alongTrack = [&](const EgoMotionParams& p) {
    std::mt19937 rng(1);
    const EgoMotion em = motionFromMatches(matches, p, {kColumn, kRow}, rng);
    EXPECT_TRUE(em.ok) << em.inliers << "/" << em.matches;
    return em.motion.translation().x();
  };
  EXPECT_NEAR(alongTrack(EgoMotionParams{}), 0.5, 0.01);
  // Without the still test, the lane-marking corners (whose spread across the ring is small) hold
  // it back; without either, the still corners outvote the moving points.
  EgoMotionParams spread_only;
  spread_only.still_match_pixels = 0;
  EXPECT_LT(alongTrack(spread_only), 0.485);
  EgoMotionParams paper = spread_only;  // the isotropic test and the closed-form fit
  paper.pixel_spread = 0;
  EXPECT_LT(alongTrack(paper), 0.25);
}

TEST(MotionFromMatches, AStillSensorKeepsItsStillMatches) {
  auto matches = streetMatches(Eigen::Isometry3d::Identity());
  for (auto& m : matches) m.still = true;  // nothing moved: every keypoint kept its pixel
  std::mt19937 rng(1);
  const EgoMotion em = motionFromMatches(matches, EgoMotionParams{}, {kColumn, kRow}, rng);
  ASSERT_TRUE(em.ok);
  EXPECT_EQ(em.inliers, em.matches);
  EXPECT_LT(em.motion.translation().norm(), 1e-6);
}

TEST(MotionFromMatches, TooFewMatchesFailWithoutAMotion) {
  const auto all = streetMatches(forward(0.5));
  const std::vector<PointMatch> few(all.begin(), all.begin() + EgoMotionParams{}.min_inliers - 1);
  std::mt19937 rng(1);
  const EgoMotion em = motionFromMatches(few, EgoMotionParams{}, {kColumn, kRow}, rng);
  EXPECT_FALSE(em.ok);
  EXPECT_EQ(em.matches, static_cast<int>(few.size()));
  EXPECT_TRUE(em.motion.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(MotionFromMatches, ParametersNameTheBadKey) {
  EgoMotionParams p;
  p.pixel_spread = -1;
  try {
    p.validate();
    FAIL() << "no error";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("pixel_spread"), std::string::npos) << e.what();
  }
  p = {};
  p.still_match_pixels = -0.5;
  try {
    p.validate();
    FAIL() << "no error";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("still_match_pixels"), std::string::npos) << e.what();
  }
}
