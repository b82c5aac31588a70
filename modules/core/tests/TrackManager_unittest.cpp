// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/ClusterAssociator.h>
#include <dynobj/core/TrackManager.h>
#include <gtest/gtest.h>

using namespace dynobj::core;
using V3 = Eigen::Vector3d;

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

TEST(TrackManager, SettledAfterSettledFramesStaticDecisionsUntilItMovesAgain) {
  TrackingParams p;
  p.confirm_frames = 2;
  p.settled_frames = 3;
  TrackManager tm(p, 5);
  MovementDecision yes, no;
  yes.enough_history = yes.candidate = true;
  no.enough_history = true;
  Track post;  // static three times in a row: settled, at rest
  for (int i = 0; i < 3; i++) tm.decide(post, no);
  EXPECT_TRUE(post.settled);
  EXPECT_TRUE(post.atRest());
  tm.decide(post, yes);  // one moving decision: still settled and static
  EXPECT_FALSE(post.dynamic);
  EXPECT_TRUE(post.settled);
  tm.decide(post, yes);  // confirm_frames in a row: it started, no longer settled
  EXPECT_TRUE(post.dynamic);
  EXPECT_FALSE(post.settled);
  Track brief;  // two static decisions are not enough to settle
  tm.decide(brief, no);
  tm.decide(brief, no);
  EXPECT_FALSE(brief.settled);
}
