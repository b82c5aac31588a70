// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/sim/PoseTrack.h>
#include <gtest/gtest.h>

using namespace dynobj::sim;

TEST(PoseTrack, WaypointsWithStartPauseAndLoop) {
  // Stand 1 s, walk (0,0) -> (10,0) at 2 m/s (5 s), pause 1 s, walk back, ...
  const auto tr = PoseTrack::waypoints({{0, 0}, {10, 0}}, 2.0, 1.0, true, 1.0, 30.0);
  EXPECT_NEAR(tr.at(0.5).x, 0.0, 1e-12);
  EXPECT_NEAR(tr.speed(0.5), 0.0, 1e-12);  // standing before the start
  EXPECT_NEAR(tr.at(3.5).x, 5.0, 1e-12);
  EXPECT_NEAR(tr.velocity(3.5).x(), 2.0, 1e-12);
  EXPECT_NEAR(tr.at(6.5).x, 10.0, 1e-12);  // pausing at the waypoint
  EXPECT_NEAR(tr.speed(6.5), 0.0, 1e-12);
  EXPECT_NEAR(tr.at(8.0).x, 8.0, 1e-12);  // walking back since t = 7
  EXPECT_NEAR(tr.velocity(8.0).x(), -2.0, 1e-12);
  EXPECT_NEAR(std::abs(tr.at(8.0).yaw), M_PI, 1e-12);
  EXPECT_GE(tr.keys().back().t, 30.0);
}

TEST(PoseTrack, StationaryNeverMoves) {
  const auto tr = PoseTrack::stationary({1, 2, 0.3});
  for (double t : {0.0, 5.0, 100.0}) {
    EXPECT_NEAR(tr.at(t).y, 2.0, 1e-12);
    EXPECT_EQ(tr.speed(t), 0.0);
  }
}

TEST(PoseTrack, RandomWalkStaysInRegionAndIsSeeded) {
  std::mt19937 a(5), b(5);
  const Eigen::Vector4d region(-3, -2, 3, 2);
  const auto t1 = PoseTrack::randomWalk(region, {0, 0}, 0.5, 1.5, 0, 2, 0, 60, a);
  const auto t2 = PoseTrack::randomWalk(region, {0, 0}, 0.5, 1.5, 0, 2, 0, 60, b);
  ASSERT_EQ(t1.keys().size(), t2.keys().size());
  for (double t = 0; t < 60; t += 0.37) {
    const Pose2 p = t1.at(t);
    EXPECT_EQ(p.x, t2.at(t).x);
    EXPECT_GE(p.x, -3.0);
    EXPECT_LE(p.x, 3.0);
    EXPECT_LE(t1.speed(t), 1.5 + 1e-9);
  }
}

TEST(PoseTrack, RejectsBadInput) {
  EXPECT_THROW(PoseTrack({{1.0, {}}, {0.5, {}}}), std::invalid_argument);
  EXPECT_THROW(PoseTrack::waypoints({}, 1, 0, true, 0, 10), std::invalid_argument);
  std::mt19937 g(1);
  EXPECT_THROW(PoseTrack::randomWalk({0, 0, 0, 1}, {0, 0}, 1, 2, 0, 0, 0, 10, g),
               std::invalid_argument);
}
