// SPDX-License-Identifier: BSD-3-Clause
// Hindsight: a track that has been dynamic for min_dynamic in the newest held frame flags its
// earlier clusters, grown over the object, back while the object was moving (seen through the
// ego-motion) and its cluster was not a merge, and no further.
#include <dynobj/core/Config.h>
#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/core/GroundSegmenter.h>
#include <dynobj/core/Hindsight.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Post;
using dynobj::test::Scene;

namespace {

constexpr int kTrack = 7;

/// Pixels whose point lies on the post at (x, y) above the floor.
std::vector<int> postPixels(const LidarFrame& f, double x, double y, double radius) {
  std::vector<int> px;
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++) {
      const cv::Vec3f& p = f.xyz(r, c);
      if (f.isValid(r, c) && std::abs(std::hypot(p[0] - x, p[1] - y) - radius) < 1e-3 &&
          p[2] > -1.0f + 0.04f)
        px.push_back(r * f.cols() + c);
    }
  return px;
}

/// A sequence of frames 0.1 s apart seeing one post (sensor frame positions `at`), each with the
/// result the detector would give: the post tracked as kTrack, its cluster = the post's upper
/// pixels only (features), its box the post's, dynamic (all its pixels flagged) in the last
/// `dynamic` frames; `motion`: each frame's T_{prev<-cur}; `standing`: posts in every frame;
/// `room_radius`: the wall around the sensor [m] (beyond max_range: no wall, nothing behind).
struct Sequence {
  std::vector<LidarFrame> frames;
  std::vector<DetectionResult> results;
  std::vector<std::vector<int>> post;  ///< every post pixel per frame

  Sequence(const std::vector<Eigen::Vector2d>& at, const Eigen::Isometry3d& motion,
           std::size_t dynamic = 3, const std::vector<Post>& standing = {},
           double room_radius = Scene().room_radius) {
    const SensorModel s = dynobj::test::smallSensor();
    for (std::size_t j = 0; j < at.size(); j++) {
      Scene scene;
      scene.room_radius = room_radius;
      scene.posts.push_back({at[j].x(), at[j].y(), 0.3, 1.8});
      scene.posts.insert(scene.posts.end(), standing.begin(), standing.end());
      frames.push_back(dynobj::test::render(scene, s, true, 1000000000LL + 100000000LL * j));
      const LidarFrame& f = frames.back();
      DetectionResult r;
      r.timestamp_ns = f.timestamp_ns;
      r.frame_index = static_cast<long>(j);
      GroundSegmenter().segment(f, r.ground);
      r.dynamic = cv::Mat_<std::uint8_t>(f.range.size(), std::uint8_t{0});
      r.seeds = r.dynamic.clone();
      r.ego_motion.motion = j == 0 ? Eigen::Isometry3d::Identity() : motion;
      post.push_back(postPixels(f, at[j].x(), at[j].y(), 0.3));
      TrackedObject o;
      o.id = kTrack;
      o.centroid = Eigen::Vector3d(at[j].x(), at[j].y(), 0);
      // The tracker's velocity, in the world (through the ego-motion): the step into this frame
      // (out of it for the first frame).
      const std::size_t a = j == 0 ? 0 : j - 1, b = std::min(a + 1, at.size() - 1);
      const Eigen::Vector3d from = motion.inverse() * Eigen::Vector3d(at[a].x(), at[a].y(), 0);
      o.velocity = b > a ? Eigen::Vector2d((at[b] - from.head<2>()) / 0.1) : Eigen::Vector2d(0, 0);
      o.box_min = o.centroid - Eigen::Vector3d(0.3, 0.3, 1);
      o.box_max = o.centroid + Eigen::Vector3d(0.3, 0.3, 0.8);
      for (int px : post.back())
        if (f.xyz(px / f.cols(), px % f.cols())[2] > 0.3f) o.cluster.push_back(px);
      o.points = static_cast<int>(o.cluster.size());
      results.push_back(r);
      results.back().objects.push_back(o);
    }
    for (std::size_t j = at.size() - dynamic; j < at.size(); j++) {
      results[j].objects[0].dynamic = true;
      for (int px : post[j]) results[j].dynamic(px / frames[j].cols(), px % frames[j].cols()) = 255;
    }
  }
  std::vector<Hindsight::Held> held() {
    std::vector<Hindsight::Held> h;
    for (std::size_t j = 0; j < frames.size(); j++) h.push_back({&frames[j], &results[j]});
    return h;
  }
  /// Frames [from, to) as if the track had not been seen there (its features fell short).
  void unseen(std::size_t from, std::size_t to) {
    for (std::size_t j = from; j < to; j++) {
      results[j].objects.clear();
      results[j].dynamic.setTo(0);
    }
  }
  /// The frame's flagged pixels, as indices.
  std::vector<int> flagged(std::size_t j) const {
    std::vector<int> px;
    for (int i = 0; i < static_cast<int>(results[j].dynamic.total()); i++)
      if (results[j].dynamic(i / results[j].dynamic.cols, i % results[j].dynamic.cols))
        px.push_back(i);
    return px;
  }
};

Eigen::Isometry3d forward(double metres) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation().x() = metres;
  return T;
}

}  // namespace

/// Frames at 1.5 m/s across the sensor's view (0.15 m per 0.1 s), `n` of them.
std::vector<Eigen::Vector2d> walking(int n) {
  std::vector<Eigen::Vector2d> at;
  for (int j = 0; j < n; j++) at.emplace_back(4, -0.15 * (n - 1 - j));
  return at;
}

TEST(Hindsight, FlagsTheWholeObjectInEveryEarlierFrameItMovedIn) {
  // Dynamic in the last 3 frames (0.3 s = min_dynamic): frames 0-3 are revised.
  Sequence seq(walking(7), forward(0));
  ASSERT_GT(seq.post[0].size(), seq.results[0].objects[0].cluster.size());
  const long added = Hindsight().revise(seq.held());
  long expected = 0;
  for (std::size_t j = 0; j < 4; j++) {
    EXPECT_EQ(seq.flagged(j), seq.post[j]) << "frame " << j;  // grown from the upper part
    EXPECT_TRUE(seq.results[j].objects[0].dynamic);
    EXPECT_EQ(seq.results[j].objects[0].points, static_cast<int>(seq.post[j].size()));
    expected += static_cast<long>(seq.post[j].size());
  }
  EXPECT_EQ(added, expected);
  EXPECT_GE(seq.results.back().timings.hindsight, 0.0);
}

TEST(Hindsight, TrustsATrackOnlyOnceItHasBeenDynamicForMinDynamic) {
  Sequence young(walking(7), forward(0), 2);  // 0.2 s: not yet
  EXPECT_EQ(Hindsight().revise(young.held()), 0);
  for (std::size_t j = 0; j < 5; j++) EXPECT_TRUE(young.flagged(j).empty()) << "frame " << j;
  // ... unless the recording ends there: nothing can tell it from a flicker any more.
  Sequence ending(walking(7), forward(0), 2);
  EXPECT_GT(Hindsight().revise(ending.held(), true), 0);
  for (std::size_t j = 0; j < 5; j++) EXPECT_EQ(ending.flagged(j), ending.post[j]) << "frame " << j;
  HindsightParams quick;
  quick.min_dynamic = 0.2;
  Hindsight(quick).revise(young.held());
  for (std::size_t j = 0; j < 5; j++) EXPECT_EQ(young.flagged(j), young.post[j]) << "frame " << j;

  // Dynamic for 4 frames: it was trusted a frame ago, when the earlier frames were revised.
  Sequence older(walking(7), forward(0), 4);
  EXPECT_EQ(Hindsight().revise(older.held()), 0);
  EXPECT_TRUE(older.flagged(2).empty());
}

TEST(Hindsight, StopsWhereTheObjectWasNotYetMovingOrWasFlaggedAlready) {
  // Standing until frame 2, then 1.5 m/s, dynamic in the last frame; min_dynamic 0: one frame
  // is trusted. Judged on the average to the last frame (speed_window 0), from frames 3, 2, 1, 0:
  // 1.5, 1.5, 1.0 and 0.75 m/s; with min_speed 0.9 frames 3 to 1 are flagged back, frame 0 not
  // (frames 1 and 2, standing, are the price of judging on the average; start_check, off here,
  // would stop at frame 2).
  Sequence seq({{4, -0.3}, {4, -0.3}, {4, -0.3}, {4, -0.15}, {4, 0}}, forward(0), 1);
  HindsightParams p;
  p.min_speed = 0.9;
  p.speed_window = 0;
  p.start_check = false;
  p.min_dynamic = 0;
  Hindsight(p).revise(seq.held());
  EXPECT_TRUE(seq.flagged(0).empty());
  for (std::size_t j = 1; j < 4; j++) EXPECT_EQ(seq.flagged(j), seq.post[j]) << "frame " << j;

  // Dynamic in frame 2, then not in 3, then again in 4-6: only the gap (frame 3) is revised.
  Sequence again(walking(7), forward(0), 3);
  again.results[2].objects[0].dynamic = true;
  again.results[2].dynamic.setTo(0);  // frame 2's pixels are the caller's: none, to see
  Hindsight().revise(again.held());
  for (std::size_t j = 0; j < 3; j++) EXPECT_TRUE(again.flagged(j).empty()) << "frame " << j;
  EXPECT_EQ(again.flagged(3), again.post[3]);
}

/// Standing in frames 0-5 at (4, -0.6), starting between frames 5 and 6, then 1.5 m/s in frames
/// 6-9, dynamic in the last two (min_dynamic 0.2 s: trusted), min_speed 0.9 m/s: the frames
/// hindsight flags with these settings.
std::vector<std::size_t> flaggedAfterAStart(double speed_window, bool start_check) {
  std::vector<Eigen::Vector2d> at(6, Eigen::Vector2d(4, -0.6));
  for (int j = 1; j <= 4; j++) at.emplace_back(4, -0.6 + 0.15 * j);
  Sequence seq(at, forward(0), 2);
  HindsightParams p;
  p.min_speed = 0.9;
  p.min_dynamic = 0.2;
  p.speed_window = speed_window;
  p.start_check = start_check;
  Hindsight(p).revise(seq.held());
  std::vector<std::size_t> frames;
  for (std::size_t j = 0; j < 8; j++)
    if (!seq.flagged(j).empty()) frames.push_back(j);
  return frames;
}

TEST(Hindsight, JudgesEachEarlierSweepOnItsOwnSpeedNotOnTheAverageToTheLast) {
  // The average speed to frame 9 reaches back into the rest: 1.0 m/s from frame 3 (0.6 m in
  // 0.6 s). Over speed_window = 0.2 s, frame 5 moves 0.3 m to frame 7 (1.5 m/s) but frame 4 only
  // 0.15 m to frame 6 (0.75 m/s): the walk back stops there. (The window alone: no start check.)
  EXPECT_EQ(flaggedAfterAStart(0.2, false), (std::vector<std::size_t>{5, 6, 7}));
  EXPECT_EQ(flaggedAfterAStart(0, false), (std::vector<std::size_t>{3, 4, 5, 6, 7}));
  HindsightParams bad;
  bad.speed_window = -1;
  EXPECT_THROW(bad.validate(), ParameterError);
}

TEST(Hindsight, DoesNotFlagTheLastSweepBeforeAStart) {
  // Over the next 0.2 s frame 5 moves 0.3 m (1.5 m/s): the window flags it. But it came into
  // frame 5 at 0 m/s from frame 4, and into frame 4 from frame 3, and left it at 1.5 m/s (a
  // quarter of that is needed on one of the two steps in): it stood at frame 5. Frame 6 came in
  // at 1.5 m/s.
  EXPECT_EQ(flaggedAfterAStart(0.2, true), (std::vector<std::size_t>{6, 7}));
  EXPECT_EQ(flaggedAfterAStart(0.2, false), (std::vector<std::size_t>{5, 6, 7}));
  // A walker moving all along is still flagged back to the first held frame, also when its
  // centroid lagged for one sweep (frame 2 where frame 1 was: a rest of one step is none).
  Sequence seq(walking(7), forward(0));
  Hindsight().revise(seq.held());
  for (std::size_t j = 0; j < 4; j++) EXPECT_EQ(seq.flagged(j), seq.post[j]) << "frame " << j;
  std::vector<Eigen::Vector2d> lag = walking(7);
  lag[2] = lag[1];
  Sequence lagged(lag, forward(0));
  Hindsight().revise(lagged.held());
  for (std::size_t j = 0; j < 4; j++) EXPECT_EQ(lagged.flagged(j), lagged.post[j]) << "frame " << j;
}

TEST(Hindsight, CountsTheWayAlongWhereTheTrackWentNotASidewaysDrift) {
  // Frames 0-3: the centroid drifts sideways (+x, 1 m/s), as a parked car's does while the sensor
  // drives past and its visible faces turn; frames 3-6: it drives off along +y at 5 m/s (dynamic
  // in 4-6). From frame 0 the way to frame 3 (speed_window later) is 0.3 m, all sideways: along
  // where it went from there (frame 6) it is 0.06 m, below min_speed x 0.3 s, and frame 0 is not
  // flagged; frames 1-3 went 0.5-1.5 m along it. start_check is off, to see this rule alone.
  const std::vector<Eigen::Vector2d> at = {{4.0, -1.5}, {4.1, -1.5}, {4.2, -1.5}, {4.3, -1.5},
                                           {4.3, -1.0}, {4.3, -0.5}, {4.3, 0.0}};
  HindsightParams p;
  p.start_check = false;
  Sequence along(at, forward(0));
  Hindsight(p).revise(along.held());
  EXPECT_TRUE(along.flagged(0).empty());
  for (std::size_t j = 1; j < 4; j++) EXPECT_EQ(along.flagged(j), along.post[j]) << "frame " << j;
  p.way_along = false;  // the whole way: 0.3 m, so frame 0 too
  Sequence drift(at, forward(0));
  Hindsight(p).revise(drift.held());
  for (std::size_t j = 0; j < 4; j++) EXPECT_EQ(drift.flagged(j), drift.post[j]) << "frame " << j;
}

TEST(Hindsight, AtTheOldestHeldSweepsTheTracksOwnSpeedThenDecides) {
  // A walker who stood until frame 0 and set off from there at 1.5 m/s (dynamic in frames 4-5).
  // Frame 0 has no step in within the held frames: the speed of its track (50 sweeps old) then
  // decides (0 m/s: standing, not flagged). Frame 1 came in at 1.5 m/s: flagged.
  std::vector<Eigen::Vector2d> at;
  for (int j = 0; j <= 5; j++) at.emplace_back(4, -1.0 + 0.15 * j);
  Sequence seq(at, forward(0), 2);
  seq.results[0].objects[0].velocity.setZero();
  seq.results[0].objects[0].age = 50;
  HindsightParams p;
  p.min_speed = 0.9;
  p.min_dynamic = 0.2;
  p.speed_window = 0.2;
  Hindsight(p).revise(seq.held());
  for (std::size_t j = 0; j < 4; j++) EXPECT_EQ(seq.flagged(j).empty(), j == 0) << "frame " << j;
  // The same frame 0 with the tracker moving then (a walk going on before the held frames):
  // flagged, as before this check.
  Sequence moving(at, forward(0), 2);
  moving.results[0].objects[0].velocity = Eigen::Vector2d(0, 1.5);
  moving.results[0].objects[0].age = 50;
  Hindsight(p).revise(moving.held());
  EXPECT_EQ(moving.flagged(0), moving.post[0]);
  // A track born two sweeps before has no speed to tell (the first sweeps of a recording):
  // flagged, as before this check.
  Sequence young(at, forward(0), 2);
  young.results[0].objects[0].velocity.setZero();
  young.results[0].objects[0].age = 2;
  Hindsight(p).revise(young.held());
  EXPECT_EQ(young.flagged(0), young.post[0]);
}

TEST(Hindsight, AFlaggedSweepAtRestDoesNotLowerTheBarForTheOneBeforeIt) {
  // At rest in frames 0-5 while its centroid drifts 0.02 m a sweep (its view changes), jumping
  // 0.06 m into frame 5; off at 1.5 m/s from frame 6; dynamic in frames 8-9. Frame 5 came in at
  // 0.6 m/s, over a quarter of 1.5: flagged. Frame 4 left at 0.6 m/s (the jump) and came in at
  // 0.2 m/s: against the jump it moved, against the start (1.5 m/s, the fastest speed out met
  // going back) it stood: not flagged.
  const std::vector<double> y{-1.0, -0.98, -0.96, -0.94, -0.92, -0.86, -0.71, -0.56, -0.41, -0.26};
  std::vector<Eigen::Vector2d> at;
  for (double v : y) at.emplace_back(4, v);
  Sequence seq(at, forward(0), 2);
  HindsightParams p;
  p.min_speed = 0.9;
  p.min_dynamic = 0.2;
  p.speed_window = 0.2;
  Hindsight(p).revise(seq.held());
  for (std::size_t j = 0; j < 8; j++) EXPECT_EQ(seq.flagged(j).empty(), j < 5) << "frame " << j;
}

TEST(Hindsight, StopsAtAClusterThatHadMergedWithSomethingElse) {
  // In frame 2 the walker's cluster took in a bench: its box 1.5 m longer, a 2.18 m diagonal
  // against the object's 0.85 m (allowed: 1.5 x 0.85 + 0.5 = 1.77 m).
  Sequence seq(walking(7), forward(0));
  seq.results[2].objects[0].box_max.x() += 1.5;
  Hindsight().revise(seq.held());
  EXPECT_EQ(seq.flagged(3), seq.post[3]);
  for (std::size_t j = 0; j < 3; j++) EXPECT_TRUE(seq.flagged(j).empty()) << "frame " << j;
  HindsightParams lenient;
  lenient.max_growth = 1.0;
  Sequence seq2(walking(7), forward(0));
  seq2.results[2].objects[0].box_max.x() += 1.5;
  Hindsight(lenient).revise(seq2.held());
  EXPECT_EQ(seq2.flagged(0), seq2.post[0]);
}

TEST(Hindsight, AnEarlierSweepDoesNotTakeWhatTheNewestFrameStillSeesThere) {
  // A runner at 3 m/s (0.3 m per sweep) starts beside someone standing at (4, -2.4), touching
  // in frame 0 and apart after that. The newest frame still sees the one standing; the runner has
  // travelled farther than its extent.
  std::vector<Eigen::Vector2d> at;
  for (int j = 0; j < 7; j++) at.emplace_back(4, -0.3 * (6 - j));
  const Post standing{4, -2.4, 0.3, 1.8};
  HindsightParams off;
  off.later_surface_check = false;
  Sequence before(at, forward(0), 3, {standing}), now(at, forward(0), 3, {standing});
  Hindsight(off).revise(before.held());
  Hindsight().revise(now.held());
  const std::vector<int> other = postPixels(now.frames[0], 4, -2.4, 0.3);
  ASSERT_FALSE(other.empty());
  // Without the check the runner's region takes the one standing; with it, only the runner.
  EXPECT_GT(before.flagged(0).size(), now.post[0].size() + other.size() / 2);
  EXPECT_EQ(now.flagged(0), now.post[0]);
  for (std::size_t j = 1; j < 4; j++) {  // nothing else to refuse
    EXPECT_EQ(now.flagged(j), now.post[j]) << "frame " << j;
    EXPECT_EQ(now.flagged(j), before.flagged(j)) << "frame " << j;
  }
}

TEST(Hindsight, AnEarlierClusterMergedWithSomeoneStandingGivesUpTheirPoints) {
  // A walker at 1.5 m/s passes someone standing at (4, -1.5): in frame 0 they touch and their
  // cluster is one (the box 1.34 m across; the walker goes only 0.9 m by the newest frame, so
  // the walker has not "travelled farther than its extent"). The newest frame still sees the
  // one standing there: their points are not the walker's, in the cluster as in the growth.
  const Post standing{4, -1.5, 0.3, 1.8};
  auto merged = [&standing] {
    Sequence seq(walking(7), forward(0), 3, {standing});
    TrackedObject& o = seq.results[0].objects[0];
    const LidarFrame& f = seq.frames[0];
    for (int px : postPixels(f, standing.x, standing.y, standing.radius))
      if (f.xyz(px / f.cols(), px % f.cols())[2] > 0.3f) o.cluster.push_back(px);
    o.box_min.y() -= 0.6;
    return seq;
  };
  Sequence before = merged(), now = merged();
  HindsightParams off;
  off.later_surface_points = false;
  Hindsight(off).revise(before.held());
  Hindsight().revise(now.held());
  const std::vector<int> other = postPixels(now.frames[0], standing.x, standing.y, 0.3);
  ASSERT_FALSE(other.empty());
  auto taken = [](const std::vector<int>& flagged, const std::vector<int>& of) {
    return std::count_if(of.begin(), of.end(), [&flagged](int px) {
      return std::find(flagged.begin(), flagged.end(), px) != flagged.end();
    });
  };
  EXPECT_GT(taken(before.flagged(0), other), static_cast<long>(other.size() / 2));
  EXPECT_EQ(taken(now.flagged(0), other), 0);
  EXPECT_GE(taken(now.flagged(0), now.post[0]), static_cast<long>(now.post[0].size() * 9 / 10));
  for (std::size_t j = 1; j < 4; j++) EXPECT_EQ(now.flagged(j), now.post[j]) << "frame " << j;
}

TEST(Hindsight, JudgesMotionThroughTheEgoMotion) {
  // The sensor drives +0.15 m per frame along x. A post standing in the world comes 0.15 m nearer
  // each frame in the sensor frame: not moving, nothing flagged back.
  Sequence still({{4.9, 0}, {4.75, 0}, {4.6, 0}, {4.45, 0}, {4.3, 0}, {4.15, 0}, {4, 0}},
                 forward(0.15));
  Hindsight().revise(still.held());
  for (std::size_t j = 0; j < 4; j++) EXPECT_TRUE(still.flagged(j).empty()) << "frame " << j;
  // A car driving ahead at the sensor's speed stays put in the sensor frame: moving, flagged.
  Sequence ahead(std::vector<Eigen::Vector2d>(7, Eigen::Vector2d(4, 0)), forward(0.15));
  Hindsight().revise(ahead.held());
  for (std::size_t j = 0; j < 4; j++) EXPECT_EQ(ahead.flagged(j), ahead.post[j]) << "frame " << j;
}

TEST(Hindsight, HeldFramesFollowTheLagAndTheRate) {
  EXPECT_EQ(Hindsight().heldFrames(10), 10);
  EXPECT_EQ(Hindsight().heldFrames(20), 20);
  HindsightParams online;
  online.lag = 0;
  EXPECT_EQ(Hindsight(online).heldFrames(10), 0);
  for (const char* key : {"min_speed", "min_dynamic", "max_growth", "lag"}) {
    HindsightParams bad;
    bad.min_speed = std::string(key) == "min_speed" ? -1 : bad.min_speed;
    bad.min_dynamic = std::string(key) == "min_dynamic" ? -1 : bad.min_dynamic;
    bad.max_growth = std::string(key) == "max_growth" ? 0 : bad.max_growth;
    bad.lag = std::string(key) == "lag" ? -1 : bad.lag;
    try {
      Hindsight{bad};
      ADD_FAILURE() << key << " accepted";
    } catch (const ParameterError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

namespace {

/// `n` frames 0.1 s apart of a post standing still in the world at x = 4 while the sensor drives
/// forward `speed` m/s, flagged (dynamic) in every frame; ego-motion known (ok).
Sequence standingPost(int n, double speed) {
  std::vector<Eigen::Vector2d> at;
  for (int j = 0; j < n; j++) at.emplace_back(4 - 0.1 * speed * j, 0.0);
  Sequence seq(at, forward(0.1 * speed), static_cast<std::size_t>(n));
  for (DetectionResult& r : seq.results) r.ego_motion.ok = true;
  return seq;
}

}  // namespace

TEST(Hindsight, StopCheckJudgesInTheWorldAndNotAcrossAFailedEgoMotion) {
  // In the sensor frame the post slides 0.2 m per frame (2 m/s, above rest_speed); in the world
  // it stands: unflagged in the first frame (pixels and object), the others kept.
  Sequence driving = standingPost(11, 2.0);
  EXPECT_EQ(Hindsight().settle(driving.held()), 1);
  EXPECT_TRUE(driving.flagged(0).empty());
  EXPECT_FALSE(driving.results[0].objects[0].dynamic);
  for (std::size_t j = 1; j < driving.frames.size(); j++)
    EXPECT_EQ(driving.flagged(j), driving.post[j]);
  EXPECT_EQ(cv::countNonZero(driving.results[0].seeds), 0);
  // The same with the ego-motion failed into frame 2: one step out of frame 0, no verdict.
  Sequence failed = standingPost(11, 2.0);
  failed.results[2].ego_motion.ok = false;
  EXPECT_EQ(Hindsight().settle(failed.held()), 0);
  EXPECT_EQ(failed.flagged(0), failed.post[0]);
}

/// A walker flagged in every frame at the positions `at` (sensor at rest), its track's speed
/// `speed` in each frame (1.5 m/s in every frame when empty); the frames in which settle()
/// unflags it, each judged as the oldest held frame (the later ones held behind it, as
/// SequenceRunner does).
std::vector<std::size_t> unflaggedOnStop(const std::vector<double>& y, bool stop_check,
                                         double rest_speed = 0,
                                         const std::vector<double>& speed = {}) {
  std::vector<Eigen::Vector2d> at;
  for (double v : y) at.emplace_back(4, v);
  Sequence seq(at, forward(0), y.size());
  for (std::size_t j = 0; j < seq.results.size(); j++) {
    seq.results[j].ego_motion.ok = true;
    seq.results[j].objects[0].velocity = Eigen::Vector2d(0, speed.empty() ? 1.5 : speed[j]);
  }
  HindsightParams p;
  p.stop_check = stop_check;
  p.rest_speed = rest_speed;
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k + 1 < y.size(); k++) {
    std::vector<Hindsight::Held> held = seq.held();
    held.erase(held.begin(), held.begin() + static_cast<std::ptrdiff_t>(k));
    if (Hindsight(p).settle(held) > 0) {
      out.push_back(k);
      EXPECT_TRUE(seq.flagged(k).empty()) << "frame " << k;
      EXPECT_FALSE(seq.results[k].objects[0].dynamic);
    } else {
      EXPECT_EQ(seq.flagged(k), seq.post[k]) << "frame " << k;
    }
  }
  return out;
}

TEST(Hindsight, StopCheckUnflagsTheSweepsWhereAWalkerHadStopped) {
  // Walks into frame 3 (0.15 m per frame), stands from there: frames 3-6 stood, the two steps
  // out of each slower than a quarter of 1.5 m/s; frame 7 has one step left (no verdict).
  const std::vector<double> stops{-1.2, -1.05, -0.9, -0.75, -0.75, -0.75, -0.75, -0.75, -0.75};
  EXPECT_EQ(unflaggedOnStop(stops, true), (std::vector<std::size_t>{3, 4, 5, 6}));
  EXPECT_TRUE(unflaggedOnStop(stops, false).empty());
  // A pause of one step is no stop: frame 3 steps out at 0 then at 1.5 m/s; motion below a
  // quarter of its speed (a creep of 0.03 m per frame, 0.3 m/s) counts as a stop.
  EXPECT_EQ(unflaggedOnStop({-1.2, -1.05, -0.9, -0.75, -0.75, -0.6, -0.45, -0.3}, true),
            (std::vector<std::size_t>{}));
  EXPECT_EQ(unflaggedOnStop({-1.2, -1.05, -0.9, -0.87, -0.84, -0.81, -0.78}, true),
            (std::vector<std::size_t>{2, 3, 4}));
}

TEST(Hindsight, RestSpeedJudgesTheNetWayOutOfASweepAfterTheTracksSpeedHasFallen) {
  // Walks into frame 3, then stands with its centroid jittering by 0.02-0.03 m per frame while
  // the tracker's speed falls (0.6 m/s in frame 4 down to 0.1): a quarter of it is below the
  // jitter, so the quarter rule unflags frame 3 only (1.2 m/s then); both steps together moved
  // 0.015 m at most (0.075 m/s), below rest_speed. Frame 7 has one step left: no verdict.
  const std::vector<double> jitter{-1.2, -1.05, -0.9, -0.75, -0.73, -0.755, -0.735, -0.745, -0.74};
  const std::vector<double> speed{1.5, 1.5, 1.5, 1.2, 0.6, 0.4, 0.2, 0.1, 0.1};
  EXPECT_EQ(unflaggedOnStop(jitter, true, 0, speed), (std::vector<std::size_t>{3}));
  EXPECT_EQ(unflaggedOnStop(jitter, true, 0.3, speed), (std::vector<std::size_t>{3, 4, 5, 6}));
  EXPECT_TRUE(unflaggedOnStop(jitter, false, 0.3, speed).empty());  // stop_check off: nothing
  // A walker at 0.5 m/s (0.05 m per step, 0.1 m over two) is still walking; so is one who
  // pauses for one step.
  EXPECT_TRUE(unflaggedOnStop({-1.0, -0.95, -0.9, -0.85, -0.8, -0.75}, true, 0.3,
                              {0.5, 0.5, 0.5, 0.5, 0.5, 0.5})
                  .empty());
  EXPECT_TRUE(
      unflaggedOnStop({-1.2, -1.05, -0.9, -0.75, -0.75, -0.6, -0.45, -0.3}, true, 0.3).empty());
}

TEST(Hindsight, RestSpeedIsValidated) {
  HindsightParams p;
  p.rest_speed = -1;
  EXPECT_THROW(p.validate(), ParameterError);
}

/// Frames at 3 m/s across the sensor's view (0.3 m per 0.1 s), `n` of them.
std::vector<Eigen::Vector2d> running(int n) {
  std::vector<Eigen::Vector2d> at;
  for (int j = 0; j < n; j++) at.emplace_back(4, -0.3 * (n - 1 - j));
  return at;
}

TEST(Hindsight, FillsTheSweepsBeforeATrackWasFirstSeenWhereItsPlaceWasSeenLeftFree) {
  // A runner whose track was first seen in frame 4 (fewer features before), dynamic in 7-9:
  // frames 4-6 are revised, and frames 0-3 take its points about where it was, back from frame
  // 4 at its speed. Frame 3's place is seen free by frame 7 (1.2 m on: farther than its extent),
  // the wall behind it, and so on back.
  Sequence seq(running(10), forward(0));
  seq.unseen(0, 4);
  Hindsight().revise(seq.held());
  for (std::size_t j = 0; j < 7; j++) {
    EXPECT_EQ(seq.flagged(j), seq.post[j]) << "frame " << j;
    ASSERT_EQ(seq.results[j].objects.size(), 1u) << "frame " << j;
    const TrackedObject& o = seq.results[j].objects[0];
    EXPECT_EQ(o.id, kTrack);
    EXPECT_TRUE(o.dynamic);
    EXPECT_EQ(o.filled, j < 4) << "frame " << j;
    EXPECT_NEAR(o.centroid.y(), -0.3 * (9 - static_cast<double>(j)), 0.15) << "frame " << j;
  }
  // Off: frames 0-3 stay as they were.
  HindsightParams off;
  off.fill_before = false;
  Sequence before(running(10), forward(0));
  before.unseen(0, 4);
  Hindsight(off).revise(before.held());
  for (std::size_t j = 0; j < 4; j++) {
    EXPECT_TRUE(before.flagged(j).empty()) << "frame " << j;
    EXPECT_TRUE(before.results[j].objects.empty()) << "frame " << j;
  }
  for (std::size_t j = 4; j < 7; j++) EXPECT_EQ(before.flagged(j), before.post[j]) << "frame " << j;
}

TEST(Hindsight, FillsNothingBeforeAFirstSightingWhosePlaceNoFrameSawFree) {
  // The same runner with no wall behind it: no later frame sees through where it was (no
  // return), so nothing proves that what stood there left: frames 0-3 are not filled.
  Sequence seq(running(10), forward(0), 3, {}, 60);
  seq.unseen(0, 4);
  Hindsight().revise(seq.held());
  for (std::size_t j = 0; j < 4; j++) EXPECT_TRUE(seq.flagged(j).empty()) << "frame " << j;
  EXPECT_EQ(seq.flagged(4), seq.post[4]);  // its sightings are revised as before
}

TEST(Hindsight, FillsTheSweepsWhereADynamicTrackWasNotSeenBetweenTwoSightings) {
  // Dynamic from frame 2 on, not seen in frames 5 and 6, seen again (dynamic) in frame 7, the
  // newest held: frames 5 and 6 take its points between the two sightings.
  for (const bool fill : {true, false}) {
    Sequence seq(running(8), forward(0), 6);
    seq.unseen(5, 7);
    HindsightParams p;
    p.fill_gaps = fill;
    Hindsight(p).revise(seq.held());
    for (std::size_t j = 5; j < 7; j++) {
      EXPECT_EQ(seq.flagged(j), fill ? seq.post[j] : std::vector<int>{}) << "frame " << j;
      EXPECT_EQ(seq.results[j].objects.size(), fill ? 1u : 0u) << "frame " << j;
    }
  }
  // Not when the sighting before the gap was not dynamic (nothing to fill between), nor when the
  // two sightings are closer than min_speed allows over the gap (a jump, not a motion).
  Sequence still(running(8), forward(0), 1);
  still.unseen(5, 7);
  Hindsight().revise(still.held());
  for (std::size_t j = 5; j < 7; j++) EXPECT_TRUE(still.flagged(j).empty()) << "frame " << j;
  std::vector<Eigen::Vector2d> at = running(8);
  at[7] = at[4] + Eigen::Vector2d(0, 0.1);  // 0.1 m in 0.3 s: 0.33 m/s < min_speed
  Sequence slow(at, forward(0), 6);
  slow.unseen(5, 7);
  Hindsight().revise(slow.held());
  for (std::size_t j = 5; j < 7; j++) EXPECT_TRUE(slow.flagged(j).empty()) << "frame " << j;
}

TEST(Hindsight, FillsNoGapWhereAnEarlierFrameSawSomethingStandThatIsNotTheObject) {
  // The runner is not there in frames 5 and 6 (it went behind the sensor: not seen), and a thin
  // post beside its way stands within reach of where it would have been. The newest frame no
  // longer sees the post (taken away), so only the earlier frames tell: frame 1, by which the
  // runner was 1.2 m away, saw the post where frame 5 sees it.
  std::vector<Eigen::Vector2d> at = running(8);
  at[5] = at[6] = Eigen::Vector2d(-4, 0);
  const Post post{4.5, -0.45, 0.1, 1.5};
  Sequence seq(at, forward(0), 6, {post});
  const Sequence gone(at, forward(0), 6);
  seq.frames[7] = gone.frames[7];
  seq.results[7] = gone.results[7];
  seq.unseen(5, 7);
  Hindsight().revise(seq.held());
  for (std::size_t j = 5; j < 7; j++) {
    EXPECT_TRUE(seq.flagged(j).empty()) << "frame " << j;
    EXPECT_TRUE(seq.results[j].objects.empty()) << "frame " << j;
  }
}
