// SPDX-License-Identifier: BSD-3-Clause
// ClusterAssociator (Eq. 8-13): the cost matrix with its dummies, one global assignment, the
// gates, and associateMoversFirst, on hand-made centroids with exact expected pairings.
#include <dynobj/core/ClusterAssociator.h>
#include <dynobj/core/Config.h>
#include <dynobj/core/Hungarian.h>
#include <gtest/gtest.h>

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

TEST(ClusterAssociator, ComponentsWithTheirOwnGatesMatchTheWholeProblem) {
  // Gates of 0.3-3 m per track, points in 3-D on both sides of the origin (the grid of the
  // widest gate that finds the pairs has cells of negative index too): the decomposed answer
  // costs what the one large Hungarian problem's optimum costs.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-6, 6), z(-1, 1), g(0.3, 3.0);
  const ClusterAssociator a;
  for (int trial = 0; trial < 40; trial++) {
    std::vector<V3> cur, pred;
    std::vector<double> gates;
    for (int i = 0; i < 30; i++) cur.emplace_back(u(rng), u(rng), z(rng));
    for (int i = 0; i < 25; i++) {
      pred.emplace_back(u(rng), u(rng), z(rng));
      gates.push_back(g(rng));
    }
    const auto out = a.associate(cur, pred, gates);
    const Eigen::MatrixXd D = a.costMatrix(cur, pred, gates);
    double whole = 2.0 * static_cast<double>(pred.size());  // every track to a dummy ...
    for (std::size_t m = 0; m < cur.size(); m++) {
      if (out[m] < 0) {
        whole += 2.0;
        continue;
      }
      const auto n = static_cast<std::size_t>(out[m]);
      ASSERT_LE((cur[m] - pred[n]).norm(), gates[n]) << "trial " << trial;
      whole += (cur[m] - pred[n]).norm() - 2.0;  // ... but this one, paired
    }
    EXPECT_NEAR(whole, assignmentCost(D, solveAssignment(D)), 1e-9) << "trial " << trial;
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
