// SPDX-License-Identifier: BSD-3-Clause
// ClusterAssociator::associateMoversFirst on hand-made centroids with exact expected pairings.
#include <dynobj/core/ClusterAssociator.h>
#include <gtest/gtest.h>

using namespace dynobj::core;

namespace {

Eigen::Vector3d at(double x, double y) {
  return {x, y, 0};
}

}  // namespace

// A van's big cluster lies 0.1 m from its track's prediction; a young track of one of its small
// fragments was predicted 0.3 m ahead of the van's, and another fragment lies 0.9 m behind it
// (1.2 m from the young track: beyond its gate). One global assignment (Eq. 10-13) pairs the big
// cluster with the young track and the fragment with the van (0.2 + 0.9) rather than leave the
// fragment and the young track unpaired (0.1 + 2 x 2 d_max): the van's track gets a fragment.
TEST(ClusterAssociator, AMoverKeepsItsOwnClusterAgainstAYoungTrackBesideIt) {
  const std::vector<Eigen::Vector3d> clusters{at(0.1, 0), at(-0.9, 0)};
  const std::vector<Eigen::Vector3d> tracks{at(0, 0), at(0.3, 0)};  // 0 = the van, 1 = young
  const std::vector<double> gates{1.0, 1.0};
  ClusterAssociator paper(AssociationParams{});
  EXPECT_EQ(paper.associate(clusters, tracks, gates), (std::vector<int>{1, 0}));
  // Movers first: the van takes its cluster (within half its gate); the far fragment is new.
  EXPECT_EQ(paper.associateMoversFirst(clusters, tracks, gates, {1, 0}), (std::vector<int>{0, -1}));
  AssociationParams off;
  off.movers_first = false;
  EXPECT_EQ(ClusterAssociator(off).associateMoversFirst(clusters, tracks, gates, {1, 0}),
            (std::vector<int>{1, 0}));
}

// A mover's own cluster is missing this sweep; a parked car's cluster lies 0.8 m from the
// mover's prediction (inside its gate, outside half of it) and 0.05 m from the car's own track.
// The first round does not hand it to the mover: the car's track takes it in the second.
TEST(ClusterAssociator, AMoverWithoutItsClusterDoesNotTakeAnObjectBesideIt) {
  const std::vector<Eigen::Vector3d> clusters{at(0.8, 0)};
  const std::vector<Eigen::Vector3d> tracks{at(0, 0), at(0.85, 0)};  // 0 = mover, 1 = parked
  ClusterAssociator a(AssociationParams{});
  EXPECT_EQ(a.associateMoversFirst(clusters, tracks, {1.0, 1.0}, {1, 0}), (std::vector<int>{1}));
  // With no other track there, the mover does take it (second round, full gate), as before.
  EXPECT_EQ(a.associateMoversFirst(clusters, {at(0, 0)}, {1.0}, {1}), (std::vector<int>{0}));
}

// In a crowd: a walker's own cluster is missing this sweep and someone standing 0.3 m from the
// walker's prediction (within half its gate) keeps their cluster; that cluster lies nearer to the
// standing person's own track, so the first round leaves it to the second, where it is theirs.
TEST(ClusterAssociator, AMoverDoesNotTakeTheClusterOfSomeoneStandingBesideIt) {
  const std::vector<Eigen::Vector3d> clusters{at(0.3, 0)};
  const std::vector<Eigen::Vector3d> tracks{at(0, 0), at(0.32, 0)};  // 0 = walker, 1 = standing
  ClusterAssociator a(AssociationParams{});
  EXPECT_EQ(a.associateMoversFirst(clusters, tracks, {1.0, 1.0}, {1, 0}), (std::vector<int>{1}));
}

TEST(ClusterAssociator, WithoutMoversItIsTheOneAssignment) {
  const std::vector<Eigen::Vector3d> clusters{at(0, 0), at(3, 0), at(10, 0)};
  const std::vector<Eigen::Vector3d> tracks{at(2.9, 0), at(0.2, 0)};
  ClusterAssociator a(AssociationParams{});
  EXPECT_EQ(a.associateMoversFirst(clusters, tracks, {1.0, 1.0}, {0, 0}),
            a.associate(clusters, tracks, {1.0, 1.0}));
  EXPECT_EQ(a.associate(clusters, tracks, {1.0, 1.0}), (std::vector<int>{1, 0, -1}));
  EXPECT_THROW(a.associateMoversFirst(clusters, tracks, {1.0, 1.0}, {1}), std::invalid_argument);
}
