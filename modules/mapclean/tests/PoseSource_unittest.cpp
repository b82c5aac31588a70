// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/PoseSource.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <gtest/gtest.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>

#include <filesystem>
#include <fstream>

#include "FrameFixture.h"

namespace mc = dynobj::mapclean;
namespace fs = std::filesystem;

namespace {

std::string tmp(const std::string& name) {
  return dynobj::mapclean::test::tmpPath(name);
}

Eigen::Isometry3d shift(double x, double y, double yaw = 0) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0);
  return T;
}

mc::Scan scanAt(std::size_t index, std::int64_t t_ns) {
  mc::Scan s;
  s.index = index;
  s.where = "entry " + std::to_string(index);
  s.frame = mc::test::tinyFrame({}, t_ns);
  s.mount.translation() = Eigen::Vector3d(0, 0, 0.5);
  return s;
}

/// Runs `fn`, expecting a std::runtime_error whose message contains every fragment.
template <class Fn>
void expectError(Fn fn, std::initializer_list<const char*> fragments) {
  try {
    fn();
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    for (const char* f : fragments)
      EXPECT_NE(std::string(e.what()).find(f), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(PoseSource, TumFileMatchesByTimestampAndNamesMissingScans) {
  const std::string f = tmp("two.tum");
  std::ofstream(f)
      << "# t x y z qx qy qz qw\n1.000000000 1 2 3 0 0 0 1\n1.100000000 4 5 6 0 0 0 1\n";
  auto src = mc::makePoseSource(f);
  const dynobj::core::EgoMotion ego;
  EXPECT_TRUE(
      src->pose(scanAt(0, 1000000000), ego).translation().isApprox(Eigen::Vector3d(1, 2, 3)));
  EXPECT_TRUE(
      src->pose(scanAt(1, 1100000400), ego).translation().isApprox(Eigen::Vector3d(4, 5, 6)));
  expectError([&] { src->pose(scanAt(2, 1200000000), ego); },
              {"two.tum", "has 2 poses, fewer than the scans", "scan 2"});
  expectError([&] { src->pose(scanAt(1, 1050000000), ego); },
              {"two.tum", "timestamps do not match", "scan 1"});
  mc::PoseSourceOptions robot;
  robot.tum_robot_poses = true;
  EXPECT_NEAR(mc::makePoseSource(f, robot)->pose(scanAt(0, 1000000000), ego).translation().z(), 3.5,
              1e-12);
}

TEST(PoseSource, MalformedTumLineIsAnErrorWithFileAndLine) {
  const std::string f = tmp("bad.tum");
  std::ofstream(f) << "1.0 1 2 3 0 0 0 1\n1.1 4 5\n";
  expectError([&] { mc::makePoseSource(f); }, {"bad.tum:2"});
}

TEST(PoseSource, UnknownFormatAndMissingFile) {
  expectError([] { mc::makePoseSource(tmp("poses.xyz")); }, {"poses.xyz", "unknown format"});
  expectError([] { mc::makePoseSource(tmp("nope.tum")); }, {"nope.tum", "does not exist"});
}

TEST(PoseSource, OdometryComposesTheMountAndNeedsOdometry) {
  auto src = mc::makePoseSource("odometry");
  auto s = scanAt(0, 0);
  expectError([&] { src->pose(s, {}); }, {"no odometry", "scan 0"});
  s.odometry = shift(2, 0, M_PI / 2);
  s.mount = shift(1, 0);
  EXPECT_TRUE(src->pose(s, {}).translation().isApprox(Eigen::Vector3d(2, 1, 0)));
}

TEST(PoseSource, EgoMotionIsChainedFromTheMount) {
  auto src = mc::makePoseSource("ego");
  dynobj::core::EgoMotion ego;
  ego.motion = shift(0.5, 0);
  auto s = scanAt(0, 0);
  s.mount = shift(0, 0.25);
  EXPECT_TRUE(src->pose(s, ego).translation().isApprox(Eigen::Vector3d(0, 0.25, 0)));
  EXPECT_TRUE(src->pose(s, ego).translation().isApprox(Eigen::Vector3d(0.5, 0.25, 0)));
  EXPECT_TRUE(src->pose(s, ego).translation().isApprox(Eigen::Vector3d(1.0, 0.25, 0)));
}

TEST(PoseSource, ViewpointNeedsPcdInput) {
  auto src = mc::makePoseSource("viewpoint");
  auto s = scanAt(3, 0);
  expectError([&] { src->pose(s, {}); }, {"KTH", "scan 3"});
  s.viewpoint = shift(7, 8);
  EXPECT_EQ(src->pose(s, {}).translation().x(), 7);
}

TEST(PoseSource, SimplemapKeyframesAndOdometryBridging) {
  // Two keyframes (t = 1 s at x = 10, t = 2 s at x = 20) with one observation each.
  mrpt::maps::CSimpleMap sm;
  for (int k = 1; k <= 2; k++) {
    auto obs = std::make_shared<mrpt::obs::CObservation3DRangeScan>();
    obs->timestamp = dynobj::mrptio::fromUnixNs(k * 1000000000LL);
    auto sf = std::make_shared<mrpt::obs::CSensoryFrame>();
    sf->insert(obs);
    sm.insert(std::make_shared<mrpt::poses::CPose3DPDFGaussian>(
                  mrpt::poses::CPose3D(10.0 * k, 0, 0, 0, 0, 0)),
              sf);
  }
  const std::string f = tmp("kf.simplemap");
  ASSERT_TRUE(sm.saveToFile(f));
  mc::PoseSourceOptions no_ego;  // --labels: no ego-motion to bridge keyframes with
  no_ego.ego_available = false;
  auto src = mc::makePoseSource(f, no_ego);
  auto s0 = scanAt(0, 500000000);  // before the first keyframe
  expectError([&] { src->pose(s0, {}); }, {"kf.simplemap", "scan 0"});
  auto s1 = scanAt(1, 1000000000);
  s1.odometry = shift(100, 0);
  EXPECT_TRUE(src->pose(s1, {}).translation().isApprox(Eigen::Vector3d(10, 0, 0.5)));
  auto s2 = scanAt(2, 1500000000);  // between keyframes: odometry moved 1.5 m since the keyframe
  s2.odometry = shift(101.5, 0);
  EXPECT_TRUE(src->pose(s2, {}).translation().isApprox(Eigen::Vector3d(11.5, 0, 0.5)));
  auto s3 = scanAt(3, 1600000000);
  expectError([&] { src->pose(s3, {}); }, {"timestamps do not match", "need odometry", "scan 3"});
  auto s4 = scanAt(4, 3000000000);  // after the last keyframe, no odometry
  expectError([&] { src->pose(s4, {}); }, {"fewer than the scans", "scan 4"});
  s4.odometry = shift(110, 0);  // with odometry: placed from the last keyframe it saw (t = 1 s)
  EXPECT_TRUE(src->pose(s4, {}).translation().isApprox(Eigen::Vector3d(20, 0, 0.5)));

  // A rawlog without odometry (icp-slam on an imported recording): between keyframes, the
  // detector's ego-motion since the last one places the scan, and describe() says so.
  auto ego_src = mc::makePoseSource(f);
  EXPECT_TRUE(
      ego_src->pose(scanAt(1, 1000000000), {}).translation().isApprox(Eigen::Vector3d(10, 0, 0.5)));
  dynobj::core::EgoMotion step;
  step.motion = shift(0.5, 0);
  EXPECT_EQ(ego_src->describe().find("ego-motion"), std::string::npos);
  ego_src->pose(scanAt(2, 1200000000), step);
  EXPECT_TRUE(ego_src->pose(scanAt(3, 1400000000), step)
                  .translation()
                  .isApprox(Eigen::Vector3d(11, 0, 0.5)));
  EXPECT_NE(ego_src->describe().find("ego-motion between keyframes"), std::string::npos);
}

TEST(PoseSource, AutoPicksOdometryElseViewpointElseEgoAndSaysWhy) {
  const dynobj::core::EgoMotion ego;
  auto with_odometry = mc::makePoseSource("auto");
  EXPECT_EQ(with_odometry->describe(), "automatic");
  auto s = scanAt(0, 1000000000);
  s.odometry = shift(3, 0);
  EXPECT_TRUE(with_odometry->pose(s, ego).translation().isApprox(Eigen::Vector3d(3, 0, 0.5)));
  EXPECT_EQ(with_odometry->describe(), "rawlog odometry (chosen: the rawlog has odometry)");

  auto with_viewpoint = mc::makePoseSource("auto");
  auto v = scanAt(0, 1000000000);
  v.viewpoint = shift(7, 0);
  EXPECT_TRUE(with_viewpoint->pose(v, ego).translation().isApprox(Eigen::Vector3d(7, 0, 0)));
  EXPECT_EQ(with_viewpoint->describe(),
            "PCD VIEWPOINT (chosen: the input has a VIEWPOINT per scan)");

  auto bare = mc::makePoseSource("auto");
  EXPECT_TRUE(bare->pose(scanAt(0, 1000000000), ego)
                  .translation()
                  .isApprox(Eigen::Vector3d(0, 0, 0.5)));  // the first scan at its mount
  EXPECT_EQ(bare->describe(), "detector ego-motion (chosen: the input has no odometry)");

  mc::PoseSourceOptions no_ego;
  no_ego.ego_available = false;
  auto labels_only = mc::makePoseSource("auto", no_ego);
  expectError([&] { labels_only->pose(scanAt(0, 1000000000), ego); },
              {"no odometry", "scan 0", "--labels", "--poses"});
}
