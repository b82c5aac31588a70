// SPDX-License-Identifier: BSD-3-Clause
// Association (Eq. 8-13), movement analysis and outlier rejection (Eq. 14-23), tracks.
#include <dynobj/core/ClusterAssociator.h>
#include <dynobj/core/Config.h>
#include <dynobj/core/Hungarian.h>
#include <dynobj/core/MovementAnalyzer.h>
#include <dynobj/core/TrackManager.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace dynobj::core;
using V3 = Eigen::Vector3d;

TEST(ClusterAssociator, CostMatrixHasDummies) {
  AssociationParams p;
  p.gate_distance = 1.0;
  const ClusterAssociator a(p);
  const auto D = a.costMatrix({V3(0, 0, 0), V3(5, 0, 0)}, {V3(0.5, 0, 0)});  // M = 2, N = 1
  ASSERT_EQ(D.rows(), 3);
  ASSERT_EQ(D.cols(), 3);
  EXPECT_DOUBLE_EQ(D(0, 0), 0.5);            // within d_max
  EXPECT_DOUBLE_EQ(D(1, 0), a.forbidden());  // beyond d_max (Eq. 9)
  EXPECT_DOUBLE_EQ(D(0, 1), 2.0);            // cluster -> dummy: 2 d_max
  EXPECT_DOUBLE_EQ(D(1, 2), 2.0);
  EXPECT_DOUBLE_EQ(D(2, 0), 2.0);  // dummy -> track
  EXPECT_DOUBLE_EQ(D(2, 1), 0.0);  // dummy -> dummy
  EXPECT_EQ(a.associate({V3(0, 0, 0), V3(5, 0, 0)}, {V3(0.5, 0, 0)}), (std::vector<int>{0, -1}));
}

TEST(ClusterAssociator, GlobalNotGreedy) {
  // Greedy nearest-neighbour would give cluster 0 track 0 (0.1) and leave cluster 1 with nothing;
  // the optimum pairs 0-1 and 1-0 (0.6 + 0.5 < 0.1 + 2 * 2 d_max).
  const ClusterAssociator a;
  EXPECT_EQ(a.associate({V3(0, 0, 0), V3(0.6, 0, 0)}, {V3(0.1, 0, 0), V3(-0.6, 0, 0)}),
            (std::vector<int>{1, 0}));
}

TEST(ClusterAssociator, ComponentsMatchTheWholeProblem) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-10, 10);
  const ClusterAssociator a;
  for (int trial = 0; trial < 30; trial++) {
    std::vector<V3> cur, pred;
    for (int i = 0; i < 25; i++) cur.emplace_back(u(rng), u(rng), 0);
    for (int i = 0; i < 20; i++) pred.emplace_back(u(rng), u(rng), 0);
    const auto out = a.associate(cur, pred);
    // Same total cost as the single big Hungarian problem.
    const Eigen::MatrixXd D = a.costMatrix(cur, pred);
    double whole = 0;
    {  // cost of the decomposed answer, completed with dummies
      double c = 0;
      int unmatched_tracks = static_cast<int>(pred.size());
      for (std::size_t m = 0; m < cur.size(); m++) {
        if (out[m] >= 0) {
          c += (cur[m] - pred[static_cast<std::size_t>(out[m])]).norm();
          unmatched_tracks--;
        } else {
          c += 2.0;
        }
      }
      c += 2.0 * unmatched_tracks;
      whole = c;
    }
    const std::vector<int> best = solveAssignment(D);
    EXPECT_NEAR(whole, assignmentCost(D, best), 1e-9) << "trial " << trial;
  }
}

TEST(ClusterAssociator, ATrackWithoutVelocityGetsAWiderGateWhenItIsVehicleSized) {
  // A car at 11 m/s, seen once, is 1.1 m on at the next 10 Hz sweep: beyond d_max = 1 m.
  AssociationParams p;
  p.gate_distance = 1.0;
  p.new_track_speed = 15;
  p.new_track_length = 1.0;
  const ClusterAssociator a(p);
  EXPECT_DOUBLE_EQ(a.gate(0, 4.5), 1.0);    // a velocity known: d_max
  EXPECT_DOUBLE_EQ(a.gate(0.1, 4.5), 2.5);  // a car seen once, 0.1 s ago
  EXPECT_DOUBLE_EQ(a.gate(0.2, 4.5), 4.0);  // ... 0.2 s ago
  EXPECT_DOUBLE_EQ(a.gate(0.1, 0.5), 1.0);  // a walker seen once: d_max
  EXPECT_DOUBLE_EQ(a.gate(-1, 4.5), 1.0);
  EXPECT_EQ(a.associate({V3(1.1, 0, 0)}, {V3(0, 0, 0)}), (std::vector<int>{-1}));
  EXPECT_EQ(a.associate({V3(1.1, 0, 0)}, {V3(0, 0, 0)}, {a.gate(0.1, 4.5)}), (std::vector<int>{0}));
  EXPECT_EQ(a.associate({V3(2.6, 0, 0)}, {V3(0, 0, 0)}, {a.gate(0.1, 4.5)}),
            (std::vector<int>{-1}));
  // Costs stay distances (Eq. 10): a cluster 0.9 m from a track with a velocity goes to it, not to
  // a wide-gated one 1.2 m away (costs in units of each gate, 0.9 against 0.48, would not).
  const auto D = a.costMatrix({V3(0, 0, 0)}, {V3(0.9, 0, 0), V3(-1.2, 0, 0)}, {1.0, 2.5});
  EXPECT_DOUBLE_EQ(D(0, 0), 0.9);
  EXPECT_DOUBLE_EQ(D(0, 1), 1.2);
  EXPECT_DOUBLE_EQ(D(0, 2), 2.0);  // cluster -> dummy: 2 d_max
  EXPECT_EQ(a.associate({V3(0, 0, 0)}, {V3(0.9, 0, 0), V3(-1.2, 0, 0)}, {1.0, 2.5}),
            (std::vector<int>{0}));
  EXPECT_EQ(a.associate({V3(0, 0, 0), V3(1.5, 0, 0)}, {V3(0.5, 0, 0), V3(-0.4, 0, 0)}, {1.0, 2.5}),
            (std::vector<int>{1, 0}));
  // 0 = the paper: d_max for every track.
  p.new_track_speed = 0;
  EXPECT_DOUBLE_EQ(ClusterAssociator(p).gate(0.1, 4.5), 1.0);
  EXPECT_THROW(a.associate({V3(0, 0, 0)}, {V3(0, 0, 0)}, {1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(a.costMatrix({V3(0, 0, 0)}, {V3(0, 0, 0)}, {1.0, 1.0}), std::invalid_argument);
  p.new_track_length = -1;
  EXPECT_THROW(p.validate(), ParameterError);
}

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

TEST(TrackManager, AStoppedOrPlainlyRefutedTrackIsReleasedAtOnce) {
  TrackingParams p;
  p.confirm_frames = 2;
  p.release_frames = 4;
  TrackManager tm(p, 5);
  Track t;
  MovementDecision yes, no, stopped;
  yes.enough_history = yes.candidate = true;
  no.enough_history = true;
  stopped.enough_history = stopped.candidate = stopped.stopped = true;
  tm.decide(t, yes);
  tm.decide(t, yes);
  ASSERT_TRUE(t.dynamic);
  tm.decide(t, no);  // one static verdict: hysteresis keeps it
  EXPECT_TRUE(t.dynamic);
  tm.decide(t, stopped);  // a clear stop: released now, not after 4 verdicts
  EXPECT_FALSE(t.dynamic);
  tm.decide(t, yes);  // and it must be confirmed again
  EXPECT_FALSE(t.dynamic);
  tm.decide(t, yes);
  EXPECT_TRUE(t.dynamic);
  // A refuted verdict (static_surface) is held by hysteresis; a plain one (refuted: hardly any of
  // its space was free) releases the track at once, as a stop does.
  MovementDecision occupied = yes;
  occupied.static_surface = true;
  tm.decide(t, occupied);
  EXPECT_TRUE(t.dynamic);
  occupied.refuted = true;
  tm.decide(t, occupied);
  EXPECT_FALSE(t.dynamic);
}

TEST(TrackManager, AMoverThatClearlyStoppedIsAtRestAtOnce) {
  // A walker who pauses is at rest (Track::atRest: its last points are its own for the split)
  // from its clear stop, not only once settled; a refuted one (a false mover) is not.
  for (const bool on : {true, false}) {
    TrackingParams p;
    p.stop_at_rest = on;
    TrackManager tm(p, 5);
    MovementDecision yes, stopped, refuted;
    yes.enough_history = yes.candidate = true;
    stopped.enough_history = stopped.candidate = stopped.stopped = true;
    refuted = yes;
    refuted.refuted = true;
    Track walker;
    tm.decide(walker, yes);
    tm.decide(walker, yes);
    ASSERT_TRUE(walker.dynamic);
    EXPECT_FALSE(walker.atRest());
    tm.decide(walker, stopped);
    EXPECT_FALSE(walker.dynamic);
    EXPECT_FALSE(walker.settled);
    EXPECT_EQ(walker.atRest(), on) << "stop_at_rest = " << on;
    tm.decide(walker, yes);  // one moving verdict: still released, still at rest
    EXPECT_EQ(walker.atRest(), on);
    tm.decide(walker, yes);  // walks on: dynamic, not at rest
    EXPECT_TRUE(walker.dynamic);
    EXPECT_FALSE(walker.atRest());
    EXPECT_FALSE(walker.halted);
    Track tree;
    tm.decide(tree, yes);
    tm.decide(tree, yes);
    tm.decide(tree, refuted);
    EXPECT_FALSE(tree.dynamic);
    EXPECT_FALSE(tree.atRest());
  }
}

TEST(TrackManager, AnEarlyStaticVerdictIsNoVerdict) {
  TrackingParams p;
  p.settled_frames = 1;
  TrackManager tm(p, 5);
  Track t;
  MovementDecision early_static;
  early_static.enough_history = true;
  early_static.early = true;
  tm.decide(t, early_static);
  EXPECT_EQ(t.negatives, 0);  // too short to prove a standstill
  EXPECT_FALSE(t.settled);
  MovementDecision full_static;
  full_static.enough_history = true;
  tm.decide(t, full_static);
  EXPECT_EQ(t.negatives, 1);
  EXPECT_TRUE(t.settled);
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

TEST(TrackManager, KalmanKeepsAnOccludedTrackAndItsWindow) {
  TrackingParams p;
  p.max_missed = 3;
  TrackManager tm(p, 5);
  const Eigen::Isometry3d still = Eigen::Isometry3d::Identity();
  auto cl = [](double y) {
    Cluster c;
    c.centroid = V3(5, y, 0);
    return std::vector<Cluster>{c};
  };
  for (long i = 0; i < 5; i++) {  // walks +0.1 m/frame in Y
    tm.predict(still, 0.1);
    std::vector<int> match(1, tm.tracks().empty() ? -1 : 0);
    tm.update(i, cl(0.1 * i), match);
  }
  const int id = tm.tracks()[0].id;
  for (long i = 5; i < 8; i++) {  // hidden for 3 frames: coasts at ~1 m/s
    tm.predict(still, 0.1);
    tm.update(i, {}, {});
  }
  ASSERT_EQ(tm.tracks().size(), 1u);
  EXPECT_NEAR(tm.tracks()[0].position().y(), 0.7, 0.1);
  tm.predict(still, 0.1);
  const ClusterAssociator a;
  const auto match = a.associate({V3(5, 0.8, 0)}, tm.predicted());
  EXPECT_EQ(match[0], 0);  // re-found where the filter predicted it
  tm.update(8, cl(0.8), match);
  EXPECT_EQ(tm.tracks()[0].id, id);
  EXPECT_EQ(tm.tracks()[0].window.size(), 5u);
  for (long i = 9; i < 13; i++) {  // gone for good: dropped after max_missed
    tm.predict(still, 0.1);
    tm.update(i, {}, {});
  }
  EXPECT_TRUE(tm.tracks().empty());
}

TEST(TrackManager, HysteresisStopsFlicker) {
  TrackingParams p;
  p.confirm_frames = 2;
  p.release_frames = 3;
  TrackManager tm(p, 5);
  Track t;
  MovementDecision yes, no;
  yes.enough_history = yes.candidate = true;
  no.enough_history = true;
  const std::vector<std::pair<MovementDecision, bool>> seq = {
      {yes, false}, {yes, true}, {no, true}, {yes, true}, {no, true}, {no, true}, {no, false}};
  for (const auto& [d, expect] : seq) {
    tm.decide(t, d);
    EXPECT_EQ(t.dynamic, expect);
  }
  p.hysteresis = false;
  TrackManager raw(p, 5);
  Track u;
  raw.decide(u, yes);
  EXPECT_TRUE(u.dynamic);
  raw.decide(u, no);
  EXPECT_FALSE(u.dynamic);
}

TEST(TrackManager, SettledTracksNeedLongerConfirmation) {
  TrackingParams p;
  p.confirm_frames = 2;
  p.settled_frames = 3;
  p.settled_confirm_frames = 4;
  TrackManager tm(p, 5);
  MovementDecision yes, no;
  yes.enough_history = yes.candidate = true;
  no.enough_history = true;
  Track fresh;  // never judged static: the usual two frames
  tm.decide(fresh, yes);
  tm.decide(fresh, yes);
  EXPECT_TRUE(fresh.dynamic);
  Track post;  // static three times in a row: settled, a two-frame flicker stays static
  for (int i = 0; i < 3; i++) tm.decide(post, no);
  EXPECT_TRUE(post.settled);
  for (int i = 0; i < 3; i++) {
    tm.decide(post, yes);
    EXPECT_FALSE(post.dynamic) << "moving decision " << i + 1;
  }
  tm.decide(post, yes);  // the fourth in a row: it really started
  EXPECT_TRUE(post.dynamic);
  EXPECT_FALSE(post.settled);
  Track brief;  // two static decisions are not enough to settle
  tm.decide(brief, no);
  tm.decide(brief, no);
  tm.decide(brief, yes);
  tm.decide(brief, yes);
  EXPECT_TRUE(brief.dynamic);
}
