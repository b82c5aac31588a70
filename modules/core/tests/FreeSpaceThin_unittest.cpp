// SPDX-License-Identifier: BSD-3-Clause
// Thin surfaces in the free-space test (docs/algorithm.md 7b, thin_frames): a fence's bar or wire
// thinner than the angle between two rays is missed by a past sweep's rays about as often as it
// is hit, so a point whose surface the rays do not resolve, seen through in the past frame, is
// free only where the frames beside it saw through it too (else no evidence either way).
#include <dynobj/core/Config.h>
#include <dynobj/core/FreeSpaceCheck.h>
#include <gtest/gtest.h>

#include <cmath>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Post;
using dynobj::test::Scene;

namespace {

constexpr double kDeg = M_PI / 180;

/// A post 3 m from the sensor at azimuth `az_deg`, radius `radius`.
Post postAt(double az_deg, double radius) {
  return {3 * std::cos(az_deg * kDeg), 3 * std::sin(az_deg * kDeg), radius, 1.8};
}

/// Frames of a still sensor (360 columns: 1 degree each, 32 rows), chained and remembered: the
/// post is in the frames where `seen` is true, missed by the rays of the others.
struct StillFrames {
  std::vector<LidarFrame> frames;
  FrameChain chain;
  FreeSpaceCheck check;
  Cluster post;  ///< the last frame's pixels on the post

  StillFrames(const Post& p, const std::vector<bool>& seen, const FreeSpaceParams& params)
      : check(params, seen.size()) {
    const SensorModel s = dynobj::test::smallSensor(32, 360);
    for (std::size_t j = 0; j < seen.size(); j++) {
      Scene scene;
      if (seen[j]) scene.posts.push_back(p);
      frames.push_back(dynobj::test::render(scene, s, true, 1 + static_cast<std::int64_t>(j)));
      chain.push(static_cast<long>(j), Eigen::Isometry3d::Identity(), true);
      if (j + 1 < seen.size()) check.remember(static_cast<long>(j), frames.back());
    }
    const LidarFrame& f = frames.back();
    for (int r = 0; r < f.rows(); r++)
      for (int c = 0; c < f.cols(); c++)
        if (f.isValid(r, c) && f.range(r, c) < 4 && f.xyz(r, c)[2] > -0.9f)
          post.pixels.push_back(r * f.cols() + c);
  }
  int columns() const {
    std::vector<int> cs;
    for (int px : post.pixels) cs.push_back(px % frames.back().cols());
    std::sort(cs.begin(), cs.end());
    return static_cast<int>(std::unique(cs.begin(), cs.end()) - cs.begin());
  }
  FreeSpaceEvidence evidence(long past) const {
    const long current = static_cast<long>(frames.size()) - 1;
    return check.evidence(frames.back(), current, post, past, chain);
  }
};

FreeSpaceParams thinFrames(int n) {
  FreeSpaceParams p;
  p.thin_frames = n;
  return p;
}

}  // namespace

TEST(FreeSpaceCheck, AnUnresolvedPointIsAlsoAskedOfTheFramesBesideThePastOne) {
  // A 2 cm wire 3 m away, on one column's ray only (0.4 of the 1-degree column): seen in frame 0,
  // missed by the rays of frames 1 and 2 (they fell beside it), seen now (frame 3).
  const Post wire = postAt(90.5, 0.01);
  const std::vector<bool> seen = {true, false, false, true};
  const StillFrames alone(wire, seen, thinFrames(0));
  ASSERT_EQ(alone.columns(), 1);
  const int n = static_cast<int>(alone.post.pixels.size());
  ASSERT_GE(n, 5);
  EXPECT_FALSE(alone.check.resolved(alone.frames.back(), alone.post.pixels[0]));
  // Against frame 1 alone: every point seen through, the motion "proven".
  const FreeSpaceEvidence one = alone.evidence(1);
  EXPECT_EQ(one.free, n);
  EXPECT_TRUE(one.provesMotion(alone.check.params()));
  // With the frames beside it (0 and 2): frame 0 met it, so no point is evidence either way.
  const StillFrames beside(wire, seen, thinFrames(1));
  const FreeSpaceEvidence three = beside.evidence(1);
  EXPECT_EQ(three.free, 0);
  EXPECT_EQ(three.occupied, 0);
  EXPECT_EQ(three.unknown, n);
  EXPECT_FALSE(three.provesMotion(beside.check.params()));
  // A frame beside it that met it does not make a point occupied; the past frame itself does.
  const StillFrames there(wire, {false, true, false, true}, thinFrames(1));
  EXPECT_EQ(there.evidence(1).occupied, n);
  // Missed by every frame tried (2, and 1 and 3 beside it; frame 4 is the current one): a mover.
  const StillFrames missed(wire, {true, false, false, false, true}, thinFrames(1));
  const FreeSpaceEvidence gone = missed.evidence(2);
  EXPECT_EQ(gone.free, n);
  EXPECT_EQ(gone.occupied, 0);
  FreeSpaceParams bad;
  bad.thin_frames = -1;
  EXPECT_THROW(bad.validate(), ParameterError);
}

TEST(FreeSpaceCheck, AResolvedPointIsAskedOfThePastFrameAlone) {
  // A post 0.6 m wide (11 columns): every point has a ray beside it in its row and in its column
  // on the post, so frame 0, which saw it, is not asked; frames 1 and 2 missed it.
  const StillFrames t(postAt(90, 0.3), {true, false, false, true}, thinFrames(2));
  ASSERT_GE(t.columns(), 9);
  for (int px : t.post.pixels) EXPECT_TRUE(t.check.resolved(t.frames.back(), px)) << px;
  const FreeSpaceEvidence e = t.evidence(2);
  EXPECT_EQ(e.occupied, 0);
  EXPECT_EQ(e.free, static_cast<int>(t.post.pixels.size()));
}
