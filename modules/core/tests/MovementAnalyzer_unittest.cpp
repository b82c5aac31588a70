// SPDX-License-Identifier: BSD-3-Clause
// Movement analysis and outlier rejection (Eq. 14-23).
#include <dynobj/core/Config.h>
#include <dynobj/core/MovementAnalyzer.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace dynobj::core;
using V3 = Eigen::Vector3d;

namespace {

/// A chain of `n` frames with the robot moving +0.1 m/frame along X (T_{prev<-cur} = +0.1 x).
FrameChain walkingChain(int n) {
  FrameChain chain(64);
  for (long i = 0; i < n; i++) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    if (i > 0) T.translation() = V3(0.1, 0, 0);
    chain.push(i, T, true);
  }
  return chain;
}

Cluster compact() {
  Cluster c;
  c.elongation = 1.0;
  c.length = 0.4;
  return c;
}

}  // namespace

TEST(MovementAnalyzer, MovingClusterFlaggedAfterKFramesStaticWithJitterNot) {
  MovementParams p;
  p.window = 5;
  p.min_window = 5;  // the paper: a full window before any verdict
  p.min_displacement = 0.25;
  const MovementAnalyzer m(p);
  const FrameChain chain = walkingChain(10);
  std::mt19937 rng(7);
  std::normal_distribution<double> jitter(0, 0.05);
  Window moving, still;
  for (long i = 0; i < 10; i++) {
    // World: the object moves +0.1 m/frame along Y; the robot moves +0.1 m/frame along X, so in the
    // sensor frame of frame i the world point (x, y) appears at (x - 0.1 i, y).
    moving.emplace_back(i, V3(5 - 0.1 * i, 0.1 * i, 0));
    still.emplace_back(i, V3(3 - 0.1 * i + jitter(rng), 2 + jitter(rng), 0));
    if (moving.size() > 5) moving.erase(moving.begin()), still.erase(still.begin());
    const auto dm = m.analyse(moving, chain, compact(), 0.1);
    const auto ds = m.analyse(still, chain, compact(), 0.1);
    EXPECT_EQ(dm.enough_history, i >= 4);
    EXPECT_EQ(dm.moving(), i >= 4) << "frame " << i;  // 0.4 m over the window
    if (i >= 4) {
      EXPECT_NEAR(dm.displacement, 0.4, 1e-9);
    }
    EXPECT_FALSE(ds.moving()) << "frame " << i << " f=" << ds.displacement << " fa=" << ds.path;
  }
}

TEST(MovementAnalyzer, YoungTrackJudgedEarlyOnlyWhenItAlreadyTravelledEpsilonD) {
  MovementParams p;
  p.window = 5;
  p.min_window = 3;
  p.min_displacement = 0.25;
  const MovementAnalyzer m(p);
  const FrameChain chain = walkingChain(10);
  Window fast, slow;
  for (long i = 0; i < 6; i++) {
    // Sensor moves +0.1 m/frame along X (walkingChain); world velocities 0.15 and 0.05 m/frame.
    fast.emplace_back(i, V3(5 - 0.1 * i, 0.15 * i, 0));
    slow.emplace_back(i, V3(5 - 0.1 * i, 0.05 * i, 0));
    if (fast.size() > 5) fast.erase(fast.begin()), slow.erase(slow.begin());
    const auto df = m.analyse(fast, chain, compact(), 0.1);
    const auto ds = m.analyse(slow, chain, compact(), 0.1);
    EXPECT_EQ(df.enough_history, i >= 2) << "frame " << i;
    EXPECT_EQ(df.early, i >= 2 && i < 4) << "frame " << i;
    // fast: f = 0.30 m after 3 observations (i = 2): > epsilon_d already.
    EXPECT_EQ(df.moving(), i >= 2) << "frame " << i;
    if (i == 2) {
      EXPECT_NEAR(df.displacement, 0.30, 1e-9);
    }
    // slow: f = 0.05 (i - first) never reaches 0.25 within 5 observations (0.20 at most).
    EXPECT_FALSE(ds.moving()) << "frame " << i;
  }
}

TEST(MovementAnalyzer, AStopShowsInTheLastObservationsBeforeTheWindowForgetsTheWalk) {
  MovementParams p;
  p.window = 5;
  p.min_window = 5;
  p.stop_window = 3;
  p.stop_speed = 0.3;
  const FrameChain chain = walkingChain(10);
  Window w;
  // World y: 0, 0.15, 0.30, 0.30, 0.30 (walks 0.3 m in two frames, then stands two frames).
  for (long i = 0; i < 5; i++)
    w.emplace_back(
        i, V3(5 - 0.1 * static_cast<double>(i), 0.15 * static_cast<double>(std::min(i, 2L)), 0));
  const auto d = MovementAnalyzer(p).analyse(w, chain, compact(), 0.1);
  EXPECT_NEAR(d.displacement, 0.30, 1e-9);  // the window alone still says "moving"
  EXPECT_TRUE(d.candidate);
  EXPECT_TRUE(d.stopped);  // the last 3 observations did not move at all
  EXPECT_FALSE(d.moving());
  p.stop_speed = 0;  // off: the paper's verdict
  const auto paper = MovementAnalyzer(p).analyse(w, chain, compact(), 0.1);
  EXPECT_FALSE(paper.stopped);
  EXPECT_TRUE(paper.moving());
  // A walker at 1.5 m/s is not "stopped" (0.3 m over the last 0.2 s).
  Window walk;
  for (long i = 0; i < 5; i++)
    walk.emplace_back(i, V3(5 - 0.1 * static_cast<double>(i), 0.15 * static_cast<double>(i), 0));
  p.stop_speed = 0.3;
  EXPECT_TRUE(MovementAnalyzer(p).analyse(walk, chain, compact(), 0.1).moving());
}

TEST(MovementAnalyzer, AHeightThatJittersWithTheFeaturesIsNotDrift) {
  // A far walker's few features sit on its head one sweep and its legs the next: the centroid's
  // height jumps 0.5 m while it walks 0.1 m/frame (world, along Y) past the moving sensor.
  MovementParams p;
  p.window = 5;
  p.min_window = 5;
  p.min_displacement = 0.25;
  const FrameChain chain = walkingChain(5);
  Window w, still;
  for (long i = 0; i < 5; i++) {
    const double z = i % 2 == 0 ? -0.5 : -1.0, x = 5 - 0.1 * static_cast<double>(i);
    w.emplace_back(i, V3(x, 0.1 * static_cast<double>(i), z));
    still.emplace_back(i, V3(x, 2, i < 4 ? -0.5 : -1.0));  // a post: its features drop
  }
  const auto d = MovementAnalyzer(p).analyse(w, chain, compact(), 0.1);
  EXPECT_NEAR(d.displacement, 0.4, 1e-9);
  EXPECT_NEAR(d.path, 0.4, 1e-9);  // horizontal steps only
  EXPECT_TRUE(d.moving());
  EXPECT_NEAR(d.velocity.z(), 0, 1e-12);
  EXPECT_FALSE(MovementAnalyzer(p).analyse(still, chain, compact(), 0.1).candidate);
  p.planar = false;  // the paper's 3-D centroids: four 0.51 m steps for 0.4 m of way, drift
  const auto paper = MovementAnalyzer(p).analyse(w, chain, compact(), 0.1);
  EXPECT_NEAR(paper.path, 4 * std::hypot(0.1, 0.5), 1e-9);
  EXPECT_TRUE(paper.drift);
  EXPECT_FALSE(paper.moving());
  // ... and the post, whose features went from its top to its foot, "moved" 0.5 m straight.
  EXPECT_TRUE(MovementAnalyzer(p).analyse(still, chain, compact(), 0.1).moving());
}

TEST(MovementAnalyzer, LongWallSlidingAlongItselfIsRejected) {
  const MovementAnalyzer m;  // window 5
  const FrameChain chain = walkingChain(5);
  Window w;
  // A wall along X beside the robot: its visible part (and centroid) slides forward with it.
  for (long i = 0; i < 5; i++)
    w.emplace_back(i, V3(2.0, 3.0, 0));  // same place in each sensor frame
  Cluster wall;
  wall.main_direction = Eigen::Vector2d(1, 0);
  wall.elongation = 8;
  wall.length = 6;
  const auto d = m.analyse(w, chain, wall, 0.1);
  EXPECT_TRUE(d.candidate);  // moves 0.4 m in the first frame's coordinates
  EXPECT_NEAR(d.angle, 0.0, 1e-9);
  EXPECT_TRUE(d.long_object);
  EXPECT_FALSE(d.moving());
  Cluster across = wall;  // the same motion across the object's axis is real motion
  across.main_direction = Eigen::Vector2d(0, 1);
  EXPECT_TRUE(m.analyse(w, chain, across, 0.1).moving());
}

TEST(MovementAnalyzer, AnUprightClusterShorterThanATwoWheelerIsLeftToTheFreeSpaceCheck) {
  // A rider seen from a car driving beside it: it moves along its own axis as far as the
  // viewpoint does, as a wall sliding by would, and its few points give no ends to tell.
  const FrameChain chain = walkingChain(5);
  Window w;
  for (long i = 0; i < 5; i++) w.emplace_back(i, V3(2.0, 3.0, 0));
  const auto clusterOf = [](double length, double height) {
    Cluster c;
    c.main_direction = Eigen::Vector2d(1, 0);
    c.elongation = 3;
    c.length = length;
    c.min = V3(1.0, 2.8, -0.9);
    c.max = V3(1.0 + length, 3.2, -0.9 + height);
    return c;
  };
  const MovementAnalyzer m;  // upright_length 2 m, upright_height 1 m
  const auto rider = m.analyse(w, chain, clusterOf(1.8, 1.6), 0.1);
  EXPECT_FALSE(rider.long_object);
  EXPECT_FALSE(rider.slides);
  EXPECT_TRUE(rider.moving());
  EXPECT_TRUE(m.analyse(w, chain, clusterOf(1.8, 0.6), 0.1).long_object);  // a car's low flank
  EXPECT_TRUE(m.analyse(w, chain, clusterOf(2.5, 1.6), 0.1).long_object);  // longer: a wall's
  Cluster fence = clusterOf(1.8, 1.6);  // a slice of a fence: flat
  fence.elongation = 30;
  EXPECT_TRUE(m.analyse(w, chain, fence, 0.1).long_object);
  MovementParams paper;
  paper.upright_length = 0;
  EXPECT_TRUE(MovementAnalyzer(paper).analyse(w, chain, clusterOf(1.8, 1.6), 0.1).long_object);
}

TEST(MovementAnalyzer, CarMovingAlongItsAxisIsARigidMoverNotAWall) {
  const MovementAnalyzer m;
  const FrameChain chain = walkingChain(5);  // the robot walks +0.1 m/frame along X
  Cluster car;
  car.main_direction = Eigen::Vector2d(1, 0);
  car.elongation = 3;
  car.length = 4;
  // A 4 m car drives +0.3 m/frame along X (its axis): in sensor frame i its centroid is at
  // (2 + 0.2 i, 3) and its ends 2 m either side. Both ends move with the centroid.
  Window w;
  for (long i = 0; i < 5; i++)
    w.emplace_back(i, V3(2 + 0.2 * i, 3, 0), V3(0.2 * i, 3, 0), V3(4 + 0.2 * i, 3, 0));
  const auto d = m.analyse(w, chain, car, 0.1);
  EXPECT_NEAR(d.displacement, 1.2, 1e-9);
  EXPECT_NEAR(d.angle, 0.0, 1e-9);
  EXPECT_TRUE(d.rigid);
  EXPECT_FALSE(d.long_object);
  EXPECT_TRUE(d.moving());
  // ... but it slides along itself while the robot moved (1.2 m <= 3 x 0.4 m): the free-space
  // check asks it for more free space (slide_free_ratio), as a rigid strip of wall would show
  // less. Across its axis, or seen from a sensor that stands still, it does not slide.
  EXPECT_TRUE(d.slides);
  Cluster across = car;
  across.main_direction = Eigen::Vector2d(0, 1);
  EXPECT_FALSE(m.analyse(w, chain, across, 0.1).slides);
  FrameChain still(16);
  for (long i = 0; i < 5; i++) still.push(i, Eigen::Isometry3d::Identity(), true);
  EXPECT_FALSE(m.analyse(w, still, car, 0.1).slides);
  // A wall whose real end stays at world x = -1 while its visible part grows with the robot's
  // view (other end at world x = 3 + 0.2 i): its centroid slides too, but one end is fixed.
  Window wall;
  for (long i = 0; i < 5; i++)
    wall.emplace_back(i, V3(1, 3, 0), V3(-1 - 0.1 * i, 3, 0), V3(3 + 0.1 * i, 3, 0));
  const auto dw = m.analyse(wall, chain, car, 0.1);
  EXPECT_TRUE(dw.candidate);
  EXPECT_FALSE(dw.rigid);
  EXPECT_TRUE(dw.long_object);
  EXPECT_FALSE(dw.slides);  // rejected by Eq. (23) already
  // rigid_tolerance = 0 restores the paper's Eq. (23) for every elongated cluster, with the
  // default long_object_ego_ratio = 0 (with 1.5 Eq. 23 would not apply to this car either: it
  // moved 1.2 m, more than 1.5 x the robot's 0.4 m).
  MovementParams paper;
  paper.rigid_tolerance = 0;
  paper.long_object_ego_ratio = 1.5;
  EXPECT_FALSE(MovementAnalyzer(paper).analyse(w, chain, car, 0.1).long_object);
  paper.long_object_ego_ratio = 0;
  EXPECT_TRUE(MovementAnalyzer(paper).analyse(w, chain, car, 0.1).long_object);
}

TEST(MovementAnalyzer, ACarPassingCloseByMovesAsItsEndsNotAsItsCentroid) {
  // A 4 m car passing the sensor: its points are densest abreast of the sensor, so its centroid
  // moves half as far as its ends (0.6 m against 1.2 m in the window's first frame). Both ends
  // moved alike: a rigid mover (rigid_ends_length), where the centroid alone calls it a wall.
  const FrameChain chain = walkingChain(5);  // the robot walks +0.1 m/frame along X
  Cluster car;
  car.main_direction = Eigen::Vector2d(1, 0);
  car.elongation = 3;
  car.length = 4;
  const auto passing = [](double half_length) {
    Window w;
    for (long i = 0; i < 5; i++) {
      const double end = 0.2 * static_cast<double>(i);
      w.emplace_back(i, V3(2 + 0.05 * static_cast<double>(i), 3, 0),
                     V3(2 - half_length + end, 3, 0), V3(2 + half_length + end, 3, 0));
    }
    return w;
  };
  const auto d = MovementAnalyzer().analyse(passing(2.0), chain, car, 0.1);
  EXPECT_NEAR(d.displacement, 0.6, 1e-9);
  EXPECT_TRUE(d.rigid);
  EXPECT_FALSE(d.long_object);
  EXPECT_TRUE(d.moving());
  MovementParams off;
  off.rigid_ends_length = 0;  // off: the lagging centroid makes it a wall
  const auto d_off = MovementAnalyzer(off).analyse(passing(2.0), chain, car, 0.1);
  EXPECT_FALSE(d_off.rigid);
  EXPECT_TRUE(d_off.long_object);
  // An object at rest is no car passing: a walker who merges with it shifts its ends.
  EXPECT_FALSE(MovementAnalyzer().analyse(passing(2.0), chain, car, 0.1, true).rigid);
  // A cluster shorter than rigid_ends_length (2 m): its ends are noise, the centroid decides.
  EXPECT_FALSE(MovementAnalyzer().analyse(passing(0.9), chain, car, 0.1).rigid);
  // Ends that moved unlike each other (one fixed, as a wall's real end) are not rigid however
  // far the other went.
  Window wall;
  for (long i = 0; i < 5; i++)
    wall.emplace_back(i, V3(2 + 0.05 * static_cast<double>(i), 3, 0),
                      V3(-0.1 * static_cast<double>(i), 3, 0),
                      V3(4 + 0.4 * static_cast<double>(i), 3, 0));
  EXPECT_FALSE(MovementAnalyzer().analyse(wall, chain, car, 0.1).rigid);
}

TEST(MovementAnalyzer, Eq23NeedsTheViewpointToHaveMovedAsFarAsTheObject) {
  // A long cluster moving along its own axis whose ends do not keep their distance (a car seen
  // head-on: its visible extent grows as it nears): not a rigid mover.
  Cluster car;
  car.main_direction = Eigen::Vector2d(1, 0);
  car.elongation = 3;
  car.length = 4;
  Window w;  // centroid +0.3 m/frame along X in the world, far end +0.1 m/frame only
  for (long i = 0; i < 5; i++)
    w.emplace_back(i, V3(2 + 0.3 * i, 3, 0), V3(0.3 * i, 3, 0), V3(4 + 0.1 * i, 3, 0));
  FrameChain still(16);
  for (long i = 0; i < 5; i++) still.push(i, Eigen::Isometry3d::Identity(), true);
  MovementParams p;
  p.long_object_ego_ratio = 0;  // the paper: Eq. (23) wherever the sensor is
  const auto paper = MovementAnalyzer(p).analyse(w, still, car, 0.1);
  EXPECT_NEAR(paper.displacement, 1.2, 1e-9);
  EXPECT_FALSE(paper.rigid);
  EXPECT_TRUE(paper.long_object);
  p.long_object_ego_ratio = 1.5;
  // A sensor standing still sees no wall slide: the object is judged on its motion alone.
  const auto d = MovementAnalyzer(p).analyse(w, still, car, 0.1);
  EXPECT_FALSE(d.long_object);
  EXPECT_TRUE(d.moving());
  // A sensor that travelled 0.4 m (walkingChain): 1.2 m > 1.5 x 0.4 m, still not a wall ...
  const FrameChain walking = walkingChain(5);
  Window moved;  // the same world motion, seen from the walking sensor
  for (long i = 0; i < 5; i++)
    moved.emplace_back(i, V3(2 + 0.2 * i, 3, 0), V3(0.2 * i, 3, 0), V3(4, 3, 0));
  EXPECT_FALSE(MovementAnalyzer(p).analyse(moved, walking, car, 0.1).long_object);
  // ... but a wall that slides with the walking sensor (f = 0.4 m <= 1.5 x 0.4 m) still is.
  Window wall;
  for (long i = 0; i < 5; i++)
    wall.emplace_back(i, V3(1, 3, 0), V3(-1 - 0.1 * i, 3, 0), V3(3 + 0.1 * i, 3, 0));
  EXPECT_TRUE(MovementAnalyzer(p).analyse(wall, walking, car, 0.1).long_object);
}

TEST(MovementAnalyzer, UnreliableEgoMotionInTheWindowGivesNoVerdict) {
  FrameChain chain(16);
  for (long i = 0; i < 6; i++) chain.push(i, Eigen::Isometry3d::Identity(), i != 3);
  Window w;
  for (long i = 1; i < 6; i++) w.emplace_back(i, V3(0.2 * i, 0, 0));
  const auto d = MovementAnalyzer().analyse(w, chain, compact(), 0.1);
  EXPECT_FALSE(d.enough_history);
  EXPECT_FALSE(d.moving());
}
