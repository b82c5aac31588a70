// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/core/FreeSpaceCheck.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Post;
using dynobj::test::Scene;

namespace {

/// Two frames of a still sensor (the scene before and after), remembered and chained, and the
/// points of the current frame within 0.35 m of a post's axis: a post's cluster.
struct TwoFrames : dynobj::test::TwoStillFrames {
  TwoFrames(const Scene& before, const Scene& after)
      : TwoStillFrames(before, after, dynobj::test::smallSensor(32, 512)) {}
  Cluster clusterAt(double x, double y) const {
    Cluster c;
    for (int r = 0; r < f1.rows(); r++)
      for (int col = 0; col < f1.cols(); col++) {
        const cv::Vec3f& p = f1.xyz(r, col);
        if (f1.isValid(r, col) && std::hypot(p[0] - x, p[1] - y) < 0.35 && p[2] > -0.7f)
          c.pixels.push_back(r * f1.cols() + col);
      }
    return c;
  }
};

}  // namespace

TEST(FreeSpaceCheck, MovedInVersusAlreadyThere) {
  Scene before, after;
  before.posts = {{5, 0, 0.3, 1.8}};                   // a post that stays
  after.posts = {{5, 0, 0.3, 1.8}, {4, 3, 0.3, 1.8}};  // and one that arrived at (4, 3)
  const TwoFrames t(before, after);
  const LidarFrame& f1 = t.f1;
  const FrameChain& chain = t.chain;
  const FreeSpaceCheck& check = t.check;
  const auto arrived = check.evidence(f1, 1, t.clusterAt(4, 3), 0, chain);
  const auto stayed = check.evidence(f1, 1, t.clusterAt(5, 0), 0, chain);
  EXPECT_GT(arrived.free, 5);
  EXPECT_EQ(arrived.occupied, 0);
  EXPECT_TRUE(arrived.supportsMotion(check.params()));
  EXPECT_GT(stayed.occupied, 5);
  EXPECT_EQ(stayed.free, 0);
  EXPECT_FALSE(stayed.supportsMotion(check.params()));
  // Unknown past frame: no verdict, the candidate is kept.
  EXPECT_TRUE(check.evidence(f1, 1, t.clusterAt(5, 0), 7, chain).supportsMotion(check.params()));
}

TEST(FreeSpaceCheck, ASpaceClearlyOccupiedAlreadyRefutesForGood) {
  // review(): the post that stayed is refuted with no free point at all (refuted: released at
  // once); the one that arrived is a mover; without any earlier frame there is no evidence, so
  // the candidate is not a mover (require_proof) but not clearly refuted either.
  Scene before, after;
  before.posts = {{5, 0, 0.3, 1.8}};
  after.posts = {{5, 0, 0.3, 1.8}, {4, 3, 0.3, 1.8}};
  const TwoFrames t(before, after);
  auto reviewed = [&](const FreeSpaceCheck& check, double x, double y) {
    MovementDecision d;
    d.enough_history = d.candidate = true;
    check.review(t.f1, 1, t.clusterAt(x, y), t.chain, 0.1, d);
    return d;
  };
  const MovementDecision stayed = reviewed(t.check, 5, 0);
  EXPECT_TRUE(stayed.static_surface);
  EXPECT_TRUE(stayed.refuted);
  const MovementDecision arrived = reviewed(t.check, 4, 3);
  EXPECT_TRUE(arrived.moving());
  EXPECT_FALSE(arrived.refuted);
  const MovementDecision unseen = reviewed(FreeSpaceCheck{}, 5, 0);
  EXPECT_TRUE(unseen.static_surface);
  EXPECT_FALSE(unseen.refuted);
  FreeSpaceParams off;
  off.release_free_ratio = 0;
  FreeSpaceCheck paper_like(off);
  paper_like.remember(0, t.f0);
  EXPECT_FALSE(reviewed(paper_like, 5, 0).refuted);
  off.release_free_ratio = 1.5;
  EXPECT_THROW(off.validate(), ParameterError);
}

TEST(FreeSpaceCheck, SawSurfaceThenTellsWhatThePastFrameSawButNotItsGround) {
  // The post that stayed was seen then where it is now; the one that arrived was not (the old
  // ray went through); a floor point is not a surface when the old frame's pixel was ground.
  Scene before, after;
  before.posts = {{5, 0, 0.3, 1.8}};
  after.posts = {{5, 0, 0.3, 1.8}, {4, 3, 0.3, 1.8}};
  TwoFrames t(before, after);
  const Cluster stayed = t.clusterAt(5, 0), arrived = t.clusterAt(4, 3);
  ASSERT_FALSE(stayed.pixels.empty());
  ASSERT_FALSE(arrived.pixels.empty());
  const auto view = t.check.pastView(t.f1, 1, 0, t.chain);
  ASSERT_TRUE(view.has_value());
  for (int px : stayed.pixels) EXPECT_TRUE(t.check.sawSurfaceThen(*view, t.f1.pointAt(px)));
  for (int px : arrived.pixels) EXPECT_FALSE(t.check.sawSurfaceThen(*view, t.f1.pointAt(px)));
  EXPECT_FALSE(t.check.pastView(t.f1, 1, 7, t.chain).has_value());  // not kept: no view
  // A floor pixel of the new frame: seen then at the same place, unless that pixel was ground.
  int floor_px = -1;
  for (int r = t.f1.rows() - 1; r >= 0 && floor_px < 0; r--)
    for (int c = 0; c < t.f1.cols(); c++)
      if (t.f1.isValid(r, c) && t.f1.xyz(r, c)[2] < -0.95f) {
        floor_px = r * t.f1.cols() + c;
        break;
      }
  ASSERT_GE(floor_px, 0);
  EXPECT_TRUE(t.check.sawSurfaceThen(*view, t.f1.pointAt(floor_px)));
  cv::Mat_<std::uint8_t> ground(t.f0.range.size(), std::uint8_t{0});
  ground(floor_px / t.f0.cols(), floor_px % t.f0.cols()) = 255;
  FreeSpaceCheck with_ground;
  with_ground.remember(0, t.f0, ground);
  const auto gview = with_ground.pastView(t.f1, 1, 0, t.chain);
  ASSERT_TRUE(gview.has_value());
  EXPECT_FALSE(with_ground.sawSurfaceThen(*gview, t.f1.pointAt(floor_px)));
  for (int px : stayed.pixels) EXPECT_TRUE(with_ground.sawSurfaceThen(*gview, t.f1.pointAt(px)));
}

TEST(FreeSpaceCheck, ObjectMovingAwayProvesMotionByTheSpaceItLeft) {
  // A post 4 m ahead moves 1 m straight away from the sensor. In the old frame, the space it
  // occupies now was hidden behind it (no verdict); now, the space it left is seen through.
  Scene before, after;
  before.posts = {{4, 0, 0.3, 1.8}};
  after.posts = {{5, 0, 0.3, 1.8}};
  const TwoFrames t(before, after);
  const LidarFrame& f1 = t.f1;
  const FrameChain& chain = t.chain;
  const FreeSpaceCheck& check = t.check;
  const Cluster c = t.clusterAt(5, 0);
  ASSERT_GT(c.pixels.size(), 5u);
  const auto hidden = check.evidence(f1, 1, c, 0, chain);
  EXPECT_EQ(hidden.free + hidden.occupied, 0);  // hidden then: no verdict either way
  EXPECT_FALSE(hidden.provesMotion(check.params()));
  const auto left = check.evidence(f1, 1, c, 0, chain, Eigen::Vector3d(1, 0, 0));
  EXPECT_GE(left.free, static_cast<int>(c.pixels.size()) / 2);
  EXPECT_EQ(left.occupied, 0);
  EXPECT_TRUE(left.provesMotion(check.params()));
  // A post that did not move: the space "left" behind it is the post itself, still occupied.
  const auto stayed = check.evidence(f1, 1, c, 0, chain, Eigen::Vector3d(0.05, 0, 0));
  EXPECT_FALSE(stayed.provesMotion(check.params()));
}

TEST(FreeSpaceCheck, ACandidateWithoutEvidenceIsNotAMoverUnlessProofIsWaived) {
  // The post moved 1 m straight away. A check that kept no earlier frame has no evidence at all:
  // it decides nothing, and the default then does not let the candidate be a mover.
  Scene before, after;
  before.posts = {{4, 0, 0.3, 1.8}};
  after.posts = {{5, 0, 0.3, 1.8}};
  const TwoFrames t(before, after);
  const Cluster c = t.clusterAt(5, 0);
  auto reviewed = [&](const FreeSpaceParams& p) {
    FreeSpaceCheck check(p);  // nothing remembered
    MovementDecision d;
    d.enough_history = d.candidate = true;  // velocity 0: no space-left-behind test
    check.review(t.f1, 1, c, t.chain, 0.1, d);
    return d;
  };
  const MovementDecision strict = reviewed(FreeSpaceParams{});  // require_proof = true
  EXPECT_TRUE(strict.static_surface);
  EXPECT_FALSE(strict.moving());
  FreeSpaceParams lenient;
  lenient.require_proof = false;
  const MovementDecision kept = reviewed(lenient);
  EXPECT_FALSE(kept.static_surface);
  EXPECT_TRUE(kept.moving());
  // With the old frame kept and the track's velocity, the space it left is seen through: proven.
  FreeSpaceCheck check{FreeSpaceParams{}};
  check.remember(0, t.f0);
  MovementDecision d;
  d.enough_history = d.candidate = true;
  d.velocity = Eigen::Vector3d(10, 0, 0);  // 1 m over dt = 0.1 s
  check.review(t.f1, 1, c, t.chain, 0.1, d);
  EXPECT_FALSE(d.static_surface);
  EXPECT_TRUE(d.moving());
}

TEST(FreeSpaceCheck, SwitchedOffItLeavesEveryDecisionAsItWas) {
  // enabled = false is the paper's detector: a candidate, proven or not, rigid or not, stays a
  // mover (it was refuted for want of evidence, which nothing can give when the check is off).
  Scene before, after;
  before.posts = {{4, 0, 0.3, 1.8}};
  after.posts = {{4, 0, 0.3, 1.8}};  // it did not move: on, the check refutes it
  const TwoFrames t(before, after);
  const Cluster c = t.clusterAt(4, 0);
  for (const bool rigid : {false, true}) {
    FreeSpaceParams off;
    off.enabled = false;
    FreeSpaceCheck check(off);
    check.remember(0, t.f0);
    MovementDecision d;
    d.enough_history = d.candidate = true;
    d.rigid = rigid;
    check.review(t.f1, 1, c, t.chain, 0.1, d);
    EXPECT_FALSE(d.static_surface) << "rigid " << rigid;
    EXPECT_TRUE(d.moving()) << "rigid " << rigid;
    FreeSpaceCheck on{FreeSpaceParams{}};
    on.remember(0, t.f0);
    MovementDecision refuted;
    refuted.enough_history = refuted.candidate = true;
    refuted.rigid = rigid;
    on.review(t.f1, 1, c, t.chain, 0.1, refuted);
    EXPECT_FALSE(refuted.moving()) << "rigid " << rigid;
  }
}

namespace {

/// A 4 x 8 frame whose range at (r, c) is depth(r, c) (0 = no return); the points' coordinates
/// do not matter to solidRatio.
template <typename Depth>
LidarFrame depthFrame(Depth depth) {
  LidarFrame f(dynobj::test::smallSensor(4, 8));
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 8; c++)
      if (const float d = depth(r, c); d > 0) f.setPixel(r, c, d, 1, cv::Vec3f(d, 0, 0), r * 8 + c);
  return f;
}

Cluster pixelsWhere(const LidarFrame& f, float lo, float hi) {
  Cluster k;
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++)
      if (f.range(r, c) >= lo && f.range(r, c) <= hi) k.pixels.push_back(r * f.cols() + c);
  return k;
}

}  // namespace

TEST(FreeSpaceCheck, SolidRatioTellsASurfaceFromFoliage) {
  const FreeSpaceParams p;  // tolerance at 5 m: 0.3 + 0.02 x 5 = 0.4 m
  // A block 3 columns wide at 5 m before a wall at 20 m: a corner pixel has 3 of 5 returning
  // neighbours on the block, an edge pixel 5 of 8, a middle one 8 of 8: every pixel is solid.
  const LidarFrame block = depthFrame([](int, int c) { return c >= 2 && c <= 4 ? 5 : 20; });
  const Cluster b = pixelsWhere(block, 4, 6);
  ASSERT_EQ(b.pixels.size(), 12u);
  EXPECT_DOUBLE_EQ(solidRatio(block, b, p), 1.0);
  // Its bottom row hidden by the wall: the two lower corners keep 3 of 8 (outline, not surface).
  const LidarFrame cut =
      depthFrame([](int r, int c) { return c >= 2 && c <= 4 && r < 3 ? 5 : 20; });
  EXPECT_DOUBLE_EQ(solidRatio(cut, pixelsWhere(cut, 4, 6), p), 7.0 / 9.0);
  // Foliage: neighbouring returns 0.8 m or more apart in depth, but along one diagonal (2 of 8).
  const LidarFrame leaves = depthFrame([](int r, int c) { return 5 + 0.8F * ((3 * r + c) % 4); });
  const Cluster l = pixelsWhere(leaves, 4, 8);
  ASSERT_EQ(l.pixels.size(), 32u);
  EXPECT_DOUBLE_EQ(solidRatio(leaves, l, p), 0.0);
  // A solid strip (8 pixels) and 4 isolated returns with no returning neighbour: 8 / 12.
  const LidarFrame half = depthFrame([](int r, int c) {
    if (c <= 1) return 5.0F;                                // a solid strip, columns 0-1
    return (c == 4 || c == 6) && r % 2 == 0 ? 5.0F : 0.0F;  // isolated returns
  });
  const Cluster h = pixelsWhere(half, 4, 6);
  ASSERT_EQ(h.pixels.size(), 12u);
  EXPECT_DOUBLE_EQ(solidRatio(half, h, p), 8.0 / 12.0);
  EXPECT_DOUBLE_EQ(solidRatio(half, Cluster{}, p), 1.0);  // nothing to judge: not porous
  // Two columns wide (a far person): no pixel inside the outline, no verdict, however ragged.
  Cluster narrow;
  for (int px : l.pixels)
    if (px % 8 == 3 || px % 8 == 4) narrow.pixels.push_back(px);
  ASSERT_EQ(narrow.pixels.size(), 8u);
  EXPECT_DOUBLE_EQ(solidRatio(leaves, narrow, p), 1.0);
  Cluster wider = narrow;
  for (int px : l.pixels)
    if (px % 8 == 5) wider.pixels.push_back(px);
  EXPECT_DOUBLE_EQ(solidRatio(leaves, wider, p), 0.0);
}

TEST(FreeSpaceCheck, ASeenThroughCandidateIsNotAMover) {
  const LidarFrame leaves = depthFrame([](int r, int c) { return 5 + 0.8F * ((3 * r + c) % 4); });
  const Cluster l = pixelsWhere(leaves, 4, 8);
  FrameChain chain;
  chain.push(0, Eigen::Isometry3d::Identity(), true);
  MovementDecision d;
  d.enough_history = d.candidate = true;
  ASSERT_TRUE(d.moving());
  FreeSpaceParams p;
  p.require_proof = false;  // no past frame here: only the seen-through test can decide
  FreeSpaceCheck(p).review(leaves, 0, l, chain, 0.1, d);
  EXPECT_FALSE(d.static_surface);
  EXPECT_TRUE(d.porous);
  EXPECT_FALSE(d.moving());
  FreeSpaceParams off = p;
  off.min_solid_ratio = 0;  // the paper: no such test
  MovementDecision kept;
  kept.enough_history = kept.candidate = true;
  FreeSpaceCheck(off).review(leaves, 0, l, chain, 0.1, kept);
  EXPECT_FALSE(kept.porous);
  EXPECT_TRUE(kept.moving());
}

namespace {

/// A 4 x 64 frame whose range at (r, c) is depth(r, c) (0 = no return), each point on its
/// pixel's ray (column centre azimuth, row elevation), as the free-space test projects them.
template <typename Depth>
LidarFrame rayFrame(Depth depth) {
  const auto s = dynobj::test::smallSensor(4, 64);
  const auto elev = s.rowElevations();
  LidarFrame f(s);
  for (int r = 0; r < s.rows; r++)
    for (int c = 0; c < s.cols; c++) {
      const float d = depth(r, c);
      if (d <= 0) continue;
      const double az = -M_PI + (c + 0.5) * 2 * M_PI / s.cols,
                   el = elev[static_cast<std::size_t>(r)];
      const cv::Vec3f p(static_cast<float>(d * std::cos(el) * std::cos(az)),
                        static_cast<float>(d * std::cos(el) * std::sin(az)),
                        static_cast<float>(d * std::sin(el)));
      f.setPixel(r, c, d, 1, p, r * s.cols + c);
    }
  return f;
}

Cluster column(const LidarFrame& f, int c) {
  Cluster k;
  for (int r = 0; r < f.rows(); r++) k.pixels.push_back(r * f.cols() + c);
  return k;
}

/// The evidence for `k` (pixels of `now`) against `before`, seen from a sensor that did not move.
FreeSpaceEvidence stillEvidence(const FreeSpaceParams& p, const LidarFrame& before,
                                const LidarFrame& now, const Cluster& k) {
  FrameChain chain;
  chain.push(0, Eigen::Isometry3d::Identity(), true);
  chain.push(1, Eigen::Isometry3d::Identity(), true);
  FreeSpaceCheck check(p);
  check.remember(0, before);
  return check.evidence(now, 1, k, 0, chain);
}

}  // namespace

TEST(FreeSpaceCheck, AnOccludingEdgeThatShiftedByAColumnIsNotFreeSpace) {
  // Before: a shelf (5 m) over columns 20-30, a wall (20 m) elsewhere, and a pole at 2 m in
  // column 45. Now, seen from a little aside, the shelf's edge covers column 31, whose own ray
  // went past it to the wall before: "free" by that ray alone, though the ray one column beside
  // stopped on the shelf. A block that arrived in column 40 has wall on both sides before, and one
  // in column 44 has the pole beside it (hidden: no verdict).
  const LidarFrame before = rayFrame([](int, int c) {
    if (c == 45) return 2.0F;
    return c >= 20 && c <= 30 ? 5.0F : 20.0F;
  });
  const LidarFrame now = rayFrame(
      [](int, int c) { return (c >= 20 && c <= 31) || c == 40 || c == 44 ? 5.0F : 20.0F; });
  auto evidence = [&](int side_rays, int c) {
    FreeSpaceParams p;
    p.side_rays = side_rays;
    return stillEvidence(p, before, now, column(now, c));
  };
  const FreeSpaceEvidence own = evidence(0, 31), beside = evidence(1, 31);
  EXPECT_EQ(own.free, 4);
  EXPECT_EQ(own.occupied, 0);
  EXPECT_EQ(beside.free, 0);
  EXPECT_EQ(beside.occupied, 4);
  const FreeSpaceEvidence arrived = evidence(1, 40);
  EXPECT_EQ(arrived.free, 4);
  EXPECT_EQ(arrived.occupied, 0);
  const FreeSpaceEvidence by_the_pole = evidence(1, 44);
  EXPECT_EQ(by_the_pole.free + by_the_pole.occupied, 0);
  EXPECT_EQ(by_the_pole.unknown, 4);
  EXPECT_EQ(evidence(0, 44).free, 4);
}

TEST(FreeSpaceCheck, ABeamThatPassedOverTheSurfaceBelowItIsNotFreeSpace) {
  // A beam grazing a horizontal surface (a car's roof) meets it at a range that changes fast with
  // its elevation. Before: the ray of row 2 in column 10 met the roof at 4 m, the other rays went
  // on to a wall at 20 m. Now a point of that roof lies at 5 m on row 1's ray: row 1 passed over
  // it before, row 2 below it did not. A point that arrived in column 30 has the wall around it.
  const LidarFrame before = rayFrame([](int r, int c) { return c == 10 && r == 2 ? 4.0F : 20.0F; });
  const LidarFrame now =
      rayFrame([](int r, int c) { return (c == 10 || c == 30) && r == 1 ? 5.0F : 20.0F; });
  auto evidence = [&](int side_rows, int c) {
    FreeSpaceParams p;
    p.side_rows = side_rows;
    Cluster k;
    k.pixels = {1 * now.cols() + c};
    return stillEvidence(p, before, now, k);
  };
  EXPECT_EQ(evidence(0, 10).free, 1);  // its own row alone: "free"
  const FreeSpaceEvidence roof = evidence(1, 10);
  EXPECT_EQ(roof.free, 0);
  EXPECT_EQ(roof.occupied, 0);
  EXPECT_EQ(roof.unknown, 1);
  EXPECT_EQ(evidence(1, 30).free, 1);
  FreeSpaceParams bad;
  bad.side_rows = -1;
  EXPECT_THROW(bad.validate(), ParameterError);
}

TEST(FreeSpaceCheck, TheGroundUnderAPointWellAboveItIsNotItsSurface) {
  // A car's bumper arrived at 5 m on row 1's ray (elevation 3.75 deg: 0.33 m above the sensor).
  // Before, row 1 saw a wall at 20 m, and row 2 below (-3.75 deg) met the road at 5.2 m, 0.65 m
  // below the bumper: near its range, but not its surface. Without the ground mask the road
  // refutes the arrival; with it the ray beside does not count, unless the point lies within
  // `clearance` of that ground (a kerb).
  const LidarFrame before = rayFrame([](int r, int c) { return c == 10 && r == 2 ? 5.2F : 20.0F; });
  const LidarFrame now = rayFrame([](int r, int c) { return c == 10 && r == 1 ? 5.0F : 20.0F; });
  cv::Mat_<std::uint8_t> road(before.rows(), before.cols(), std::uint8_t{0});
  road(2, 10) = 1;
  Cluster bumper;
  bumper.pixels = {1 * now.cols() + 10};
  auto evidence = [&](double clearance, const cv::Mat_<std::uint8_t>& ground) {
    FreeSpaceParams p;
    p.clearance = clearance;
    FrameChain chain;
    chain.push(0, Eigen::Isometry3d::Identity(), true);
    chain.push(1, Eigen::Isometry3d::Identity(), true);
    FreeSpaceCheck check(p);
    check.remember(0, before, ground);
    return check.evidence(now, 1, bumper, 0, chain);
  };
  const FreeSpaceEvidence unmasked = evidence(0.25, {});
  EXPECT_EQ(unmasked.occupied, 1);
  EXPECT_EQ(unmasked.free, 0);
  const FreeSpaceEvidence masked = evidence(0.25, road);
  EXPECT_EQ(masked.free, 1);
  EXPECT_EQ(masked.occupied, 0);
  const FreeSpaceEvidence kerb = evidence(1.0, road);  // 0.65 m counts as on the ground
  EXPECT_EQ(kerb.occupied, 1);
  FreeSpaceParams bad;
  bad.clearance = -0.1;
  EXPECT_THROW(bad.validate(), ParameterError);
}

TEST(FreeSpaceCheck, ASlowCandidateIsComparedWithAnOlderFrame) {
  // A walker 20 m away: ranges there agree within 0.3 + 0.02 x 20 = 0.7 m, so in lookback = 10
  // frames (1 s at 10 Hz) it must move clear_tolerances x 0.7 = 1.4 m: at 1.1 m/s it is compared
  // with the frame 13 back, at 5 m/s with the usual 10, at 0.2 m/s with max_lookback = 20. The
  // sensor's own travel since then bounds it (max_travel = 3 m).
  FreeSpaceParams p;
  const FreeSpaceCheck check(p);
  Cluster walker;
  walker.centroid = {0, 20, 0};
  auto lookback = [&](double speed, double sensor_step) {
    FrameChain chain(32);
    for (long i = 0; i <= 30; i++) {
      Eigen::Isometry3d step = Eigen::Isometry3d::Identity();
      step.translation().x() = i > 0 ? sensor_step : 0;
      chain.push(i, step, true);
    }
    MovementDecision d;
    d.velocity = {speed, 0, 0};
    return check.lookbackFor(walker, d, chain, 30, 0.1);
  };
  EXPECT_EQ(lookback(1.1, 0), 13);
  EXPECT_EQ(lookback(5.0, 0), 10);
  EXPECT_EQ(lookback(0.2, 0), 20);
  EXPECT_EQ(lookback(0.2, 0.25), 12);  // 12 steps of 0.25 m: 3 m
  EXPECT_EQ(lookback(0.2, 0.5), 10);   // never shorter than lookback
  FreeSpaceParams off = p;
  off.max_lookback = 0;
  MovementDecision slow;
  slow.velocity = {0.2, 0, 0};
  EXPECT_EQ(FreeSpaceCheck(off).lookbackFor(walker, slow, FrameChain(32), 30, 0.1), 10);
}

TEST(FreeSpaceCheck, AnObjectComingOutFromBehindAnOccluderHasNotLeftAnySpace) {
  // Before, a post at 3 m hid a post at 6 m; now the near one has gone and the far one, unmoved,
  // is in view. Its track may seem to recede (more of it shows): the space in front of it is seen
  // through now, but the old frame never saw the post there, so nothing proves it moved. A post
  // that really moved away from 5 m to 6 m was seen where it was.
  Scene before, after;
  before.posts = {{3, 0, 0.3, 1.8}, {6, 0, 0.3, 1.8}};
  after.posts = {{6, 0, 0.3, 1.8}};
  const TwoFrames t(before, after);
  const Cluster c = t.clusterAt(6, 0);
  ASSERT_GT(c.pixels.size(), 5u);
  const auto came_out = t.check.evidence(t.f1, 1, c, 0, t.chain, Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(came_out.free, 0);
  EXPECT_FALSE(came_out.provesMotion(t.check.params()));
  Scene moved_before;
  moved_before.posts = {{5, 0, 0.3, 1.8}};
  const TwoFrames m(moved_before, after);
  const auto left =
      m.check.evidence(m.f1, 1, m.clusterAt(6, 0), 0, m.chain, Eigen::Vector3d(1, 0, 0));
  EXPECT_GT(left.free, 5);
  EXPECT_TRUE(left.provesMotion(m.check.params()));
}

// FreeSpaceParams::exclude_own_past (docs/algorithm.md 7b): a long object that moves along itself
// by less than its length covered its own rear part in the past frame; those points are no
// evidence either way.

namespace {

/// A "car" of five touching posts (x from 0 to 2.4 m, 3 m to the left of a still sensor) that
/// drove 1 m forward (+x) between frame 0 and frame 1: its rear 1.4 m is where its front was.
struct CarAlong : dynobj::test::TwoStillFrames {
  Cluster car;  ///< frame 1's points on it

  /// Five touching posts from x = `x0` - 0.3 on.
  static Scene car5(double x0) {
    Scene s;
    for (int i = 0; i < 5; i++) s.posts.push_back({x0 + 0.45 * i, 3, 0.3, 1.8});
    return s;
  }
  explicit CarAlong(const FreeSpaceParams& p = {})
      : TwoStillFrames(car5(0.3), car5(1.3), dynobj::test::smallSensor(32, 720), p) {
    for (int r = 0; r < f1.rows(); r++)
      for (int c = 0; c < f1.cols(); c++) {
        const cv::Vec3f& q = f1.xyz(r, c);
        if (f1.isValid(r, c) && std::abs(q[1] - 3) < 0.5 && q[0] < 5 && q[2] > -0.7f)
          car.pixels.push_back(r * f1.cols() + c);
      }
  }
  FreeSpaceEvidence evidence(bool own_past) const {
    return check.evidence(f1, 1, car, 0, chain, Eigen::Vector3d(1, 0, 0), {}, own_past);
  }
};

}  // namespace

TEST(FreeSpaceCheck, ALongObjectsRearWhereItsFrontWasIsNoEvidence) {
  const CarAlong t;
  ASSERT_GT(t.car.pixels.size(), 40u);
  // Every point counted: the rear was the car itself then, and outweighs the new front.
  const FreeSpaceEvidence all = t.evidence(false);
  EXPECT_GT(all.occupied, all.free);
  EXPECT_FALSE(all.provesMotion(t.check.params()));
  EXPECT_EQ(all.free + all.occupied + all.unknown, static_cast<int>(t.car.pixels.size()));
  // Its own past body left out: only the front 1 m (+ margin) is asked, and it was free then.
  const FreeSpaceEvidence front = t.evidence(true);
  EXPECT_EQ(front.occupied, 0);
  EXPECT_GE(front.free, t.check.params().min_evidence);
  EXPECT_TRUE(front.provesMotion(t.check.params(), true));  // even as a sliding cluster
  EXPECT_EQ(front.free + front.occupied + front.unknown, static_cast<int>(t.car.pixels.size()));
  // Which points are left out follows the motion's direction: read backwards (the car reversing
  // 1 m), the part left out is the other end, and the evidence differs.
  const FreeSpaceEvidence reversed =
      t.check.evidence(t.f1, 1, t.car, 0, t.chain, Eigen::Vector3d(-1, 0, 0), {}, true);
  EXPECT_GT(reversed.occupied, 0);
}

TEST(FreeSpaceCheck, ReviewLeavesOutTheOwnPastOnlyForARigidMoverAndWhenOn) {
  MovementDecision rigid;  // a rigid long object moving along itself at 1 m/s (dt 1 s)
  rigid.enough_history = rigid.candidate = rigid.rigid = rigid.slides = true;
  rigid.velocity = Eigen::Vector3d(1, 0, 0);
  FreeSpaceParams p;
  p.lookback = 1;
  p.max_lookback = 1;
  const CarAlong on(p);
  MovementDecision d = rigid;
  on.check.review(on.f1, 1, on.car, on.chain, 1.0, d);
  EXPECT_FALSE(d.static_surface);
  MovementDecision not_rigid = rigid;  // a compact or non-rigid candidate: every point counts
  not_rigid.rigid = not_rigid.slides = false;
  on.check.review(on.f1, 1, on.car, on.chain, 1.0, not_rigid);
  EXPECT_TRUE(not_rigid.static_surface);
  p.exclude_own_past = false;
  const CarAlong off(p);
  d = rigid;
  off.check.review(off.f1, 1, off.car, off.chain, 1.0, d);
  EXPECT_TRUE(d.static_surface);
}

// Thin surfaces in the free-space test (docs/algorithm.md 7b, thin_frames): a fence's bar or wire
// thinner than the angle between two rays is missed by a past sweep's rays about as often as it
// is hit, so a point whose surface the rays do not resolve, seen through in the past frame, is
// free only where the frames beside it saw through it too (else no evidence either way).

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
