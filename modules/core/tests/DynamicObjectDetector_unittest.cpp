// SPDX-License-Identifier: BSD-3-Clause
// The whole pipeline on rendered scenes. Weak clusters (beyond the paper, docs/algorithm.md §5): a
// cluster with fewer than min_points features but at least weak_min_points seeds the region
// growing of a track that is already dynamic and found no cluster of its own (coasting); it never
// starts or confirms a track. A dynamic track whose features joined a cluster too large to keep
// is carved out of it ([association] carve_dropped).
#include <dynobj/core/DynamicObjectDetector.h>
#include <gtest/gtest.h>

#include <cmath>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Scene;

namespace {

/// Pixels flagged dynamic in a result.
int flaggedCount(const DetectionResult& r) {
  return cv::countNonZero(r.dynamic);
}

/// Points of `f` flagged dynamic in `r` for which `in(point)` holds.
template <class In>
int flaggedWhere(const LidarFrame& f, const DetectionResult& r, In in) {
  int n = 0;
  for (int px = 0; px < f.rows() * f.cols(); px++)
    n += f.isValid(px / f.cols(), px % f.cols()) && r.dynamic(px / f.cols(), px % f.cols()) &&
         in(f.pointAt(px));
  return n;
}

/// A post walking across the view at 1.5 m/s, 4 m ahead of a static sensor (external identity
/// ego-motion), `tall` for its first `tall_frames` frames and `height` metres tall after them.
/// Returns the pixels flagged in each frame.
std::vector<int> walk(const DetectorParams& p, int frames, int tall_frames, double height) {
  const SensorModel s = dynobj::test::smallSensor();
  DynamicObjectDetector det(p);
  std::vector<int> flagged;
  for (int j = 0; j < frames; j++) {
    Scene scene;
    scene.posts.push_back({4.0, -1.5 + 0.15 * j, 0.3, j < tall_frames ? 1.8 : height});
    const LidarFrame f = dynobj::test::render(scene, s, true, 1000000000LL + 100000000LL * j);
    flagged.push_back(flaggedCount(det.process(f, Eigen::Isometry3d::Identity())));
  }
  return flagged;
}

/// min_points between the short post's features (~10 at 0.4 m) and the tall post's (~150).
DetectorParams params(int weak_min_points) {
  DetectorParams p;
  p.clustering.min_points = 30;
  p.clustering.weak_min_points = weak_min_points;
  return p;
}

}  // namespace

TEST(DynamicObjectDetector, AMoverWhoseFeaturesDipBelowMinPointsStaysFlaggedOnAWeakCluster) {
  // The post is dynamic by frame 9; from frame 10 on only its lower 0.4 m remain (fewer
  // features than min_points, more than weak_min_points).
  const std::vector<int> with = walk(params(4), 13, 10, 0.4);
  const std::vector<int> without = walk(params(0), 13, 10, 0.4);
  ASSERT_GT(with[9], 0) << "the tall post was never found dynamic";
  EXPECT_EQ(without[9], with[9]);  // the same until the post shrinks
  for (int j = 10; j < 13; j++) {
    EXPECT_GT(with[j], 0) << "frame " << j;
    EXPECT_EQ(without[j], 0) << "frame " << j;
  }
}

TEST(DynamicObjectDetector, AWeakClusterNeverStartsATrack) {
  // The short post walks from the first frame: only weak clusters, never flagged.
  for (int flagged : walk(params(4), 13, 0, 0.4)) EXPECT_EQ(flagged, 0);
}

namespace {

/// A post walking at 1.5 m/s across the view 4 m ahead of a static sensor, past a post that
/// stands at (4.3, 0.9), just behind its path and touching it around frame 13 (their outlines
/// 0.1 m apart). Per frame, the pixels flagged on the standing post (first) and on the walker.
std::vector<std::pair<int, int>> walkPast(bool past_surface_check) {
  DetectorParams p;
  p.region_growing.keep_out_settled = false;  // the growth alone
  p.region_growing.past_surface_check = past_surface_check;
  const SensorModel s = dynobj::test::smallSensor(16, 720);
  DynamicObjectDetector det(p);
  std::vector<std::pair<int, int>> flagged;
  for (int j = 0; j < 18; j++) {
    const double y = -1.5 + 0.15 * j;
    Scene scene;
    scene.posts.push_back({4.0, y, 0.3, 1.8});
    scene.posts.push_back({4.3, 0.9, 0.25, 1.8});
    const LidarFrame f = dynobj::test::render(scene, s, true, 1000000000LL + 100000000LL * j);
    const DetectionResult& r = det.process(f, Eigen::Isometry3d::Identity());
    flagged.emplace_back(
        flaggedWhere(f, r,
                     [](const cv::Vec3f& q) { return std::hypot(q[0] - 4.3, q[1] - 0.9) < 0.26; }),
        flaggedWhere(f, r,
                     [y](const cv::Vec3f& q) { return std::hypot(q[0] - 4.0, q[1] - y) < 0.31; }));
  }
  return flagged;
}

}  // namespace

TEST(DynamicObjectDetector, AMoverDoesNotTakeTheStandingPostItTouches) {
  // The walker is dynamic long before it reaches the post and has travelled 1.5 m over the
  // free-space lookback (1 s), farther than its 0.6 m: the post's points, which the lookback
  // frame saw where they are, are refused to its region (only those among its seeds remain,
  // where the two posts' features formed one cluster).
  const auto off = walkPast(false), on = walkPast(true);
  int post_off = 0, post_on = 0;
  for (std::size_t j = 0; j < off.size(); j++) {
    post_off += off[j].first;
    post_on += on[j].first;
    // The walker keeps its pixels (all of them until frame 14, where the two posts' outlines
    // meet: 215 of 221 there).
    EXPECT_GE(on[j].second, off[j].second * 95 / 100) << "frame " << j;
    EXPECT_LE(on[j].second, off[j].second) << "frame " << j;
  }
  EXPECT_GT(post_off, 200);              // the growth took the post (148 + 104 + 44 pixels)
  EXPECT_LT(post_on, post_off * 3 / 4);  // 62 + 58 + 44
  EXPECT_GT(off[10].second, 0) << "the walker was never flagged";
}

namespace {

/// A post (radius 0.3 m) walking at 1.5 m/s across the view 4 m ahead of a static sensor, along a
/// "hedge" of thin posts just behind its path from y = 0 on (outlines 0.05 m apart): once beside
/// it, the walker's features and the hedge's form one cluster, larger than `max_area` allows.
/// Per frame, the pixels flagged on the walker (first) and on the hedge.
std::vector<std::pair<int, int>> walkAlongHedge(bool carve) {
  DetectorParams p;
  p.clustering.max_area = 2.0;  // the walker alone is less, the hedge more
  p.association.carve_dropped = carve;
  const SensorModel s = dynobj::test::smallSensor(16, 720);
  DynamicObjectDetector det(p);
  std::vector<std::pair<int, int>> flagged;
  for (int j = 0; j < 30; j++) {
    const double y = -3.0 + 0.15 * j;
    Scene scene;
    scene.posts.push_back({4.0, y, 0.3, 1.8});
    for (double h = 0; h < 4.0; h += 0.25) scene.posts.push_back({4.3, h, 0.1, 1.6, 150});
    const LidarFrame f = dynobj::test::render(scene, s, true, 1000000000LL + 100000000LL * j);
    const DetectionResult& r = det.process(f, Eigen::Isometry3d::Identity());
    const auto walker = [y](const cv::Vec3f& q) { return std::hypot(q[0] - 4.0, q[1] - y) < 0.31; };
    flagged.emplace_back(flaggedWhere(f, r, walker), flaggedWhere(f, r, [&](const cv::Vec3f& q) {
                           return !walker(q) && q[0] > 4.15 && q[0] < 4.45;
                         }));
  }
  return flagged;
}

}  // namespace

TEST(DynamicObjectDetector, AMoverMergedWithAClusterTooLargeToKeepIsCarvedOutOfIt) {
  // Until frame 16 the walker has a cluster of its own and is flagged either way (from frame 3).
  // From frame 17 on its features join the hedge's, and that cluster is dropped: without
  // carving the walker coasts without seeds and is lost (12 of the 13 frames: 0 pixels); with
  // it, the features around its prediction whose space was free a second before are its cluster,
  // and nothing of the hedge is taken that was not taken without it.
  const auto off = walkAlongHedge(false), on = walkAlongHedge(true);
  ASSERT_GT(off[10].first, 100) << "the walker was never flagged";
  int lost_off = 0, hedge_off = 0, hedge_on = 0;
  for (std::size_t j = 0; j < off.size(); j++) {
    if (j < 17) {
      EXPECT_EQ(on[j], off[j]) << "frame " << j;  // no carving before the merge
    } else {
      EXPECT_GE(on[j].first, 200) << "frame " << j;  // 207-234 pixels of ~221
      lost_off += off[j].first == 0;
    }
    hedge_off += off[j].second;
    hedge_on += on[j].second;
  }
  EXPECT_GE(lost_off, 10);
  EXPECT_LE(hedge_on, hedge_off);
}
