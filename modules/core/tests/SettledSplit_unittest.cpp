// SPDX-License-Identifier: BSD-3-Clause
// splitSettled (docs/algorithm.md §5): a cluster that holds a walker and one who stands is split
// between their tracks by the standing one's last points.
#include <dynobj/core/ClusterAssociator.h>
#include <dynobj/core/Config.h>
#include <dynobj/core/SettledSplit.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "SyntheticScene.h"

using namespace dynobj::core;

namespace {

/// Eight points in a vertical column (rows 4..11, column `col`) at (x, y), 0.1 m apart in z.
void column(LidarFrame& f, int col, float x, float y, std::vector<int>& pixels) {
  for (int r = 4; r < 12; r++) {
    const float z = 0.1f * static_cast<float>(8 - r);
    f.setPixel(r, col, std::hypot(x, y, z), 1.f, cv::Vec3f(x, y, z), r * 100 + col);
    pixels.push_back(r * f.cols() + col);
  }
}

struct MergeScene {
  LidarFrame frame{dynobj::test::smallSensor(16, 64)};
  std::vector<int> rest_px, walker_px;  ///< the two parts of the merged cluster
  std::vector<Cluster> clusters;
  std::vector<Track> tracks;  ///< [0] settled at rest, [1] dynamic (a walker)
  std::vector<Eigen::Vector3d> predicted;
  FrameChain chain;

  /// One who stands at (3, 0) (two columns of points 0.1 m apart) and a walker at (3, 0.6) with
  /// `walker_columns` columns, in one cluster. The sensor moved `travel` m forward (x) between
  /// sweep 0, where the standing one's shape was kept, and sweep 1, this one.
  /// `dy` [m] moves the whole scene sideways (negative coordinates).
  explicit MergeScene(int walker_columns = 2, double travel = 0.5, float dy = 0.f) {
    column(frame, 30, 3.0f, dy, rest_px);
    column(frame, 31, 3.0f, dy + 0.1f, rest_px);
    for (int i = 0; i < walker_columns; i++)
      column(frame, 36 + i, 3.0f, dy + 0.6f + 0.1f * static_cast<float>(i), walker_px);
    Cluster merged;
    merged.pixels = rest_px;
    merged.pixels.insert(merged.pixels.end(), walker_px.begin(), walker_px.end());
    computeClusterShape(frame, merged);
    clusters.push_back(merged);

    Track rest;
    rest.id = 7;
    rest.settled = true;
    rest.shape_frame = 0;
    for (int px : rest_px) {  // where it stood, seen from sweep 0: `travel` m farther
      const cv::Vec3f& p = frame.pointAt(px);
      rest.shape.emplace_back(p[0] + static_cast<float>(travel), p[1], p[2]);
    }
    Track walker;
    walker.id = 8;
    walker.dynamic = true;
    tracks = {rest, walker};
    predicted = {{3.0, dy + 0.05, 0.0}, {3.0, dy + 0.65, 0.0}};
    chain.push(0, Eigen::Isometry3d::Identity(), true);
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();  // T_{0<-1}
    motion.translation().x() = travel;
    chain.push(1, motion, true);
  }

  void split(std::vector<int>& cluster_to_track, double radius = 0.2,
             double min_share = SettledSplitParams{}.min_share,
             double match_radius = SettledSplitParams{}.match_radius,
             bool rest_majority = SettledSplitParams{}.rest_majority,
             std::vector<int>* held = nullptr) {
    SettledSplitParams p;
    p.radius = radius;
    p.min_share = min_share;
    p.match_radius = match_radius;
    p.rest_majority = rest_majority;
    splitSettled(p, frame, 1, chain, tracks, predicted, clusters, cluster_to_track, held);
  }

  static std::vector<int> sorted(std::vector<int> v) {
    std::sort(v.begin(), v.end());
    return v;
  }
};

}  // namespace

TEST(SettledSplit, TheWalkersClusterGivesTheStandingOneItsPoints) {
  MergeScene s;
  std::vector<int> to_track = {1};  // the walker took the merged cluster
  s.split(to_track);
  ASSERT_EQ(s.clusters.size(), 2u);
  ASSERT_EQ(to_track, (std::vector<int>{1, 0}));
  EXPECT_EQ(MergeScene::sorted(s.clusters[0].pixels), MergeScene::sorted(s.walker_px));
  EXPECT_EQ(MergeScene::sorted(s.clusters[1].pixels), MergeScene::sorted(s.rest_px));
  EXPECT_NEAR(s.clusters[0].centroid.y(), 0.65, 1e-5);  // shapes recomputed
  EXPECT_NEAR(s.clusters[1].centroid.y(), 0.05, 1e-5);
}

TEST(SettledSplit, AWalkerWhoJustStoppedIsAtRestToo) {
  // One who paused a moment ago (released by a clear stop, not settled): their points are theirs.
  MergeScene s;
  s.tracks[0].settled = false;
  std::vector<int> ignored = {1};
  s.split(ignored);
  EXPECT_EQ(s.clusters.size(), 1u);  // neither settled nor stopped: no split
  MergeScene paused;
  paused.tracks[0].settled = false;
  paused.tracks[0].halted = true;
  std::vector<int> to_track = {1};
  paused.split(to_track);
  ASSERT_EQ(to_track, (std::vector<int>{1, 0}));
  EXPECT_EQ(MergeScene::sorted(paused.clusters[0].pixels), MergeScene::sorted(paused.walker_px));
  EXPECT_EQ(MergeScene::sorted(paused.clusters[1].pixels), MergeScene::sorted(paused.rest_px));
}

TEST(SettledSplit, NegativeCoordinatesSplitTheSame) {
  MergeScene s(2, 0.5, -5.f);  // both at y < 0 (the shape's grid cells are negative)
  std::vector<int> to_track = {1};
  s.split(to_track);
  ASSERT_EQ(s.clusters.size(), 2u);
  EXPECT_EQ(MergeScene::sorted(s.clusters[1].pixels), MergeScene::sorted(s.rest_px));
}

TEST(SettledSplit, TheStandingOnesClusterGivesTheWalkerItsPoints) {
  MergeScene s;
  std::vector<int> to_track = {0};  // the standing one took it: the walker found none
  s.split(to_track);
  ASSERT_EQ(s.clusters.size(), 2u);
  ASSERT_EQ(to_track, (std::vector<int>{0, 1}));
  EXPECT_EQ(MergeScene::sorted(s.clusters[0].pixels), MergeScene::sorted(s.rest_px));
  EXPECT_EQ(MergeScene::sorted(s.clusters[1].pixels), MergeScene::sorted(s.walker_px));
}

TEST(SettledSplit, TheShapeIsMovedWithTheSensor) {
  // The shape kept in sweep 0 lies 0.5 m farther; carried into sweep 1 it meets the points. Read
  // in the wrong direction (or not moved) it would lie 0.5-1 m away and nothing would split.
  MergeScene moved(2, 0.5), still(2, 0.0);
  std::vector<int> a = {1}, b = {1};
  moved.split(a);
  still.split(b);
  EXPECT_EQ(moved.clusters.size(), 2u);
  EXPECT_EQ(still.clusters.size(), 2u);
  MergeScene forgotten(2, 0.5);
  forgotten.chain.clear();  // the shape's sweep is no longer in the chain: no split
  forgotten.chain.push(1, Eigen::Isometry3d::Identity(), true);
  std::vector<int> c = {1};
  forgotten.split(c);
  EXPECT_EQ(forgotten.clusters.size(), 1u);
  EXPECT_EQ(c, (std::vector<int>{1}));
}

/// A resting object of four columns and a walker's one column beside it: the walker's part is a
/// fifth of the merged cluster.
MergeScene smallPart() {
  MergeScene small(1);
  small.tracks[0].shape.clear();
  for (int col : {32, 33}) {
    std::vector<int> more;
    column(small.frame, col, 3.0f, 0.1f * static_cast<float>(col - 30), more);
    small.clusters[0].pixels.insert(small.clusters[0].pixels.end(), more.begin(), more.end());
  }
  for (int px : small.clusters[0].pixels) {
    const cv::Vec3f& p = small.frame.pointAt(px);
    if (p[1] < 0.55f) small.tracks[0].shape.emplace_back(p[0] + 0.5f, p[1], p[2]);
  }
  computeClusterShape(small.frame, small.clusters[0]);
  return small;
}

TEST(SettledSplit, AMoverThatIsASmallPartOfItKeepsCoasting) {
  // A false mover (a tree) that found no cluster and touches a resting object must not live on
  // the resting object's edge: a part of 8 of 40 points (a fifth), 0.15 m from where its track
  // expected it, is not taken; 16 of 32 is.
  MergeScene small = smallPart(), fair(2);
  small.predicted[1] = {3.0, 0.75, 0.0};
  fair.predicted[1] = {3.0, 0.75, 0.0};
  std::vector<int> a = {0}, b = {0};
  MergeScene lenient = small;
  small.split(a);
  EXPECT_EQ(small.clusters.size(), 1u);
  EXPECT_EQ(a, (std::vector<int>{0}));
  fair.split(b);
  EXPECT_EQ(fair.clusters.size(), 2u);
  // [association] split_min_share = 0.15: a fifth is a part.
  std::vector<int> c = {0};
  lenient.split(c, 0.2, 0.15);
  EXPECT_EQ(lenient.clusters.size(), 2u);
  AssociationParams bad;
  bad.split_min_share = 0.6;  // both parts cannot hold more than half
  EXPECT_THROW(bad.validate(), ParameterError);
}

TEST(SettledSplit, ASmallPartWhereTheMoverWasExpectedIsTheMovers) {
  // A walker beside a wall: a fifth of the merged cluster, but its centroid 0.05 m from the
  // walker's prediction (split_match_radius 0.1 m): the cluster is split. With 0, it is not.
  MergeScene s = smallPart(), off = smallPart();
  std::vector<int> a = {0}, b = {0};
  s.split(a);
  ASSERT_EQ(s.clusters.size(), 2u);
  EXPECT_EQ(a, (std::vector<int>{0, 1}));
  EXPECT_EQ(MergeScene::sorted(s.clusters[1].pixels), MergeScene::sorted(s.walker_px));
  off.split(b, 0.2, SettledSplitParams{}.min_share, 0.0);
  EXPECT_EQ(off.clusters.size(), 1u);
  EXPECT_EQ(b, (std::vector<int>{0}));
  AssociationParams bad;
  bad.split_match_radius = -0.1;
  EXPECT_THROW(bad.validate(), ParameterError);
}

TEST(SettledSplit, TheStandingOneAloneIsTakenFromTheMover) {
  // The walker's track took a cluster that is only the standing one (the walker is hidden):
  // the cluster goes to the standing one's track, the walker coasts.
  MergeScene s(0);
  std::vector<int> to_track = {1};
  s.split(to_track);
  EXPECT_EQ(s.clusters.size(), 1u);
  EXPECT_EQ(to_track, (std::vector<int>{0}));
}

TEST(SettledSplit, NothingChangesWhenOffOrWhenBothAreAlike) {
  MergeScene off;
  std::vector<int> a = {1};
  off.split(a, 0.0);
  EXPECT_EQ(off.clusters.size(), 1u);
  EXPECT_EQ(a, (std::vector<int>{1}));
  MergeScene both_rest;  // two tracks at rest merged: not this rule's business
  both_rest.tracks[1].dynamic = false;
  both_rest.tracks[1].settled = true;
  std::vector<int> b = {1};
  both_rest.split(b);
  EXPECT_EQ(both_rest.clusters.size(), 1u);
  MergeScene far;  // the standing one's prediction is nowhere near the cluster
  far.predicted[0] = {8.0, 5.0, 0.0};
  std::vector<int> c = {1};
  far.split(c);
  EXPECT_EQ(far.clusters.size(), 1u);
}

TEST(SettledSplit, RememberShapesKeepsOnlyTracksAtRest) {
  MergeScene s;
  s.tracks[0].cluster = 0;
  s.tracks[1].cluster = 0;
  s.tracks[1].shape = {Eigen::Vector3f(1, 2, 3)};
  rememberShapes(s.frame, 4, s.clusters, {}, s.tracks);
  EXPECT_EQ(s.tracks[0].shape.size(), s.clusters[0].pixels.size());
  EXPECT_EQ(s.tracks[0].shape_frame, 4);
  EXPECT_TRUE(s.tracks[1].shape.empty());
  EXPECT_EQ(s.tracks[1].shape_frame, -1);
}

TEST(SettledSplit, TheMoversPartMustLieWhereTheMoverWasExpected) {
  // The walker's track expected it 0.5 m from where its part lies (a false mover wandering over a
  // fence, or a resting object's face the walker hid): no split, whichever took it. Taken by the
  // walker's track, the cluster, half of it the standing one's, goes to the standing one's
  // (split_rest_majority; the walker coasts); without that rule nothing changes.
  MergeScene s, kept;
  s.predicted[1] = {3.0, 1.15, 0.0};
  kept.predicted[1] = {3.0, 1.15, 0.0};
  std::vector<int> a = {1}, b = {0}, c = {1};
  s.split(a);
  EXPECT_EQ(s.clusters.size(), 1u);
  EXPECT_EQ(a, (std::vector<int>{0}));
  kept.split(c, 0.2, SettledSplitParams{}.min_share, SettledSplitParams{}.match_radius, false);
  EXPECT_EQ(kept.clusters.size(), 1u);
  EXPECT_EQ(c, (std::vector<int>{1}));
  MergeScene wide(3);  // the standing one's part less than half (16 of 40): the walker keeps it
  wide.predicted[1] = {3.0, 1.25, 0.0};
  std::vector<int> d = {1};
  wide.split(d);
  EXPECT_EQ(d, (std::vector<int>{1}));
  MergeScene t;
  t.predicted[1] = {3.0, 1.15, 0.0};
  t.split(b);
  EXPECT_EQ(t.clusters.size(), 1u);
  EXPECT_EQ(b, (std::vector<int>{0}));
}

TEST(SettledSplit, AMoversClusterHoldsBackTheRestingObjectsFairPart) {
  // The walker's part lies off its prediction (its own far side came into view) and the standing
  // one holds less than half of the cluster: the walker's track keeps it whole, but the standing
  // one's 16 points are held back (not its to flag). Every other outcome holds nothing back.
  const double d = SettledSplitParams{}.min_share, m = SettledSplitParams{}.match_radius;
  MergeScene wide(3);
  wide.predicted[1] = {3.0, 1.25, 0.0};
  std::vector<int> a = {1}, held;
  wide.split(a, 0.2, d, m, true, &held);
  EXPECT_EQ(a, (std::vector<int>{1}));
  ASSERT_EQ(wide.clusters.size(), 1u);
  EXPECT_EQ(MergeScene::sorted(held), MergeScene::sorted(wide.rest_px));

  MergeScene split;  // split: each track has its part, nothing held back
  std::vector<int> b = {1}, none;
  split.split(b, 0.2, d, m, true, &none);
  EXPECT_EQ(split.clusters.size(), 2u);
  EXPECT_TRUE(none.empty());
  MergeScene majority;  // half of it the standing one's: the cluster is its own
  majority.predicted[1] = {3.0, 1.15, 0.0};
  std::vector<int> c = {1};
  majority.split(c, 0.2, d, m, true, &none);
  EXPECT_EQ(c, (std::vector<int>{0}));
  EXPECT_TRUE(none.empty());
  MergeScene resting_took_it = wide;  // the standing one's track took it: the walker coasts
  std::vector<int> e = {0};
  resting_took_it.split(e, 0.2, d, m, true, &none);
  EXPECT_EQ(e, (std::vector<int>{0}));
  EXPECT_TRUE(none.empty());
  MergeScene small(7);  // a resting sliver (16 of 72) in the mover's cluster: a car's end over
  small.predicted[1] = {3.0, 1.25, 0.0};  // a small thing it hid keeps its points
  std::vector<int> f = {1};
  small.split(f, 0.2, d, m, true, &none);
  EXPECT_EQ(f, (std::vector<int>{1}));
  EXPECT_TRUE(none.empty());
}

TEST(SettledSplit, AResterGivenItsPartKeepsItsShape) {
  MergeScene s;
  std::vector<int> to_track = {1};
  const std::vector<int> resting =
      splitSettled({}, s.frame, 1, s.chain, s.tracks, s.predicted, s.clusters, to_track);
  ASSERT_EQ(resting, (std::vector<int>{7}));
  s.tracks[0].cluster = 1;  // its part
  const std::vector<Eigen::Vector3f> before = s.tracks[0].shape;
  rememberShapes(s.frame, 1, s.clusters, resting, s.tracks);
  EXPECT_EQ(s.tracks[0].shape, before);  // not the part (a merge may hide some of it)
  EXPECT_EQ(s.tracks[0].shape_frame, 0);
}
