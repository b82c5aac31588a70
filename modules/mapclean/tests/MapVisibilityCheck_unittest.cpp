// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/MapCleaner.h>
#include <dynobj/mapclean/MapVisibilityCheck.h>
#include <gtest/gtest.h>

#include <cmath>

#include "FrameFixture.h"

namespace mc = dynobj::mapclean;

namespace {

// The tiny sensor: rows at +15, +5, -5, -15 deg; 8 columns of 45 deg, column c centred on
// azimuth -180 + 22.5 + 45 c deg.
cv::Vec3f beam(int row, int col, float range) {
  const double el = (15.0 - 10.0 * row) * M_PI / 180.0,
               az = (-180.0 + 22.5 + 45.0 * col) * M_PI / 180.0;
  return cv::Vec3f(static_cast<float>(range * std::cos(el) * std::cos(az)),
                   static_cast<float>(range * std::cos(el) * std::sin(az)),
                   static_cast<float>(range * std::sin(el)));
}

/// Every pixel returns at `range`, except the overrides (range <= 0: no return).
dynobj::core::LidarFrame frameAt(
    float range, std::vector<std::pair<std::pair<int, int>, float>> overrides = {}) {
  std::vector<std::pair<std::pair<int, int>, cv::Vec3f>> pts;
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 8; c++) {
      float rg = range;
      for (const auto& [rc, v] : overrides)
        if (rc == std::pair{r, c}) rg = v;
      if (rg > 0) pts.push_back({{r, c}, beam(r, c, rg)});
    }
  return mc::test::tinyFrame(pts);
}

mc::VisibilityParams params() {
  mc::VisibilityParams p;
  p.margin = 0.3;
  p.margin_rel = 0.05;  // tolerance at 5 m: 0.55 m
  p.window = 1;
  p.min_views = 2;
  p.ratio = 2.0;
  return p;
}

const Eigen::Isometry3d kOrigin = Eigen::Isometry3d::Identity();

/// A voxel at 5 m in the middle of pixel (2, 4).
std::vector<mc::VoxelCentre> oneVoxel() {
  const cv::Vec3f v = beam(2, 4, 5.f);
  return {{42, v[0], v[1], v[2]}};
}

}  // namespace

TEST(MapVisibilityCheck, AVoxelSeenThroughByLaterScansIsRemoved) {
  mc::MapVisibilityCheck check(params(), oneVoxel());
  check.addScan(frameAt(5.f), kOrigin);      // a person stood there: a hit
  check.addScan(frameAt(10.f), kOrigin);     // gone: every beam reaches the wall behind
  EXPECT_TRUE(check.seenThrough().empty());  // one see-through view is not enough (min_views 2)
  check.addScan(frameAt(10.f), kOrigin);
  EXPECT_EQ(check.hitViews(0), 1);
  EXPECT_EQ(check.freeViews(0), 2);
  EXPECT_EQ(check.seenThrough(), (std::vector<std::uint64_t>{42}));
}

TEST(MapVisibilityCheck, EarlierScansCountToo) {
  mc::MapVisibilityCheck check(params(), oneVoxel());
  check.addScan(frameAt(10.f), kOrigin);
  check.addScan(frameAt(10.f), kOrigin);
  check.addScan(frameAt(5.f), kOrigin);
  EXPECT_EQ(check.seenThrough(), (std::vector<std::uint64_t>{42}));
}

TEST(MapVisibilityCheck, AWallVoxelSeenAtAGrazingAngleIsKept) {
  // The pixel itself ends 1 m beyond the voxel, but its neighbour (same row, next column) hits
  // the same wall at 4.9 m: the wall recedes within the beam. The window's nearest return is not
  // beyond the voxel, so no see-through view.
  const auto grazing = frameAt(6.f, {{{2, 3}, 4.9f}});
  mc::MapVisibilityCheck check(params(), oneVoxel());
  for (int i = 0; i < 4; i++) check.addScan(grazing, kOrigin);
  EXPECT_EQ(check.freeViews(0), 0);
  EXPECT_TRUE(check.seenThrough().empty());
  auto no_window = params();  // without the window the same views would remove it
  no_window.window = 0;
  mc::MapVisibilityCheck naive(no_window, oneVoxel());
  for (int i = 0; i < 4; i++) naive.addScan(grazing, kOrigin);
  EXPECT_EQ(naive.seenThrough().size(), 1u);
}

TEST(MapVisibilityCheck, ReturnsWithinTheMarginAreHitsNotSeeThrough) {
  mc::MapVisibilityCheck check(params(), oneVoxel());
  check.addScan(frameAt(5.5f), kOrigin);  // 0.5 m beyond: within 0.3 + 5 % of 5 m
  check.addScan(frameAt(5.5f), kOrigin);
  EXPECT_EQ(check.freeViews(0), 0);
  EXPECT_EQ(check.hitViews(0), 2);
}

TEST(MapVisibilityCheck, OccludedOrMissingReturnsGiveNoEvidence) {
  mc::MapVisibilityCheck check(params(), oneVoxel());
  check.addScan(frameAt(3.f), kOrigin);                    // something in front hides the voxel
  check.addScan(frameAt(10.f, {{{2, 4}, 0.f}}), kOrigin);  // no return in its pixel
  EXPECT_EQ(check.freeViews(0), 0);
  EXPECT_EQ(check.hitViews(0), 0);
}

TEST(MapVisibilityCheck, StaticVoxelsHitOftenAreKept) {
  mc::MapVisibilityCheck check(params(), oneVoxel());
  for (int i = 0; i < 3; i++) check.addScan(frameAt(5.f), kOrigin);
  for (int i = 0; i < 5; i++) check.addScan(frameAt(10.f), kOrigin);  // 5 < ratio 2 x 3 hits
  EXPECT_TRUE(check.seenThrough().empty());
  check.addScan(frameAt(10.f), kOrigin);  // 6 >= 2 x 3
  EXPECT_EQ(check.seenThrough().size(), 1u);
}

TEST(MapVisibilityCheck, UsesTheScanPose) {
  // The voxel is 5 m along +x of the world; the sensor stands 2 m further back along x.
  const cv::Vec3f v = beam(2, 4, 5.f);
  Eigen::Isometry3d back = Eigen::Isometry3d::Identity();
  back.translation() = Eigen::Vector3d(-2.0 * v[0] / 5.0, -2.0 * v[1] / 5.0, -2.0 * v[2] / 5.0);
  mc::MapVisibilityCheck check(params(), oneVoxel());
  check.addScan(frameAt(7.f), back);  // 7 m from there: the voxel itself
  check.addScan(frameAt(12.f), back);
  EXPECT_EQ(check.hitViews(0), 1);
  EXPECT_EQ(check.freeViews(0), 1);
}

mc::MapCleaner streamingCleaner() {
  mc::MapCleanParams p;
  p.voxel_size = 1.0;
  p.visibility = params();
  p.free_space_stride = 1;
  return mc::MapCleaner(p);
}

const cv::Mat_<std::uint8_t> kAllStatic(4, 8, std::uint8_t{0});

TEST(MapCleaner, AVoxelLaterScansSeeThroughMovesToTheDynamicMap) {
  mc::MapCleaner cleaner = streamingCleaner();
  const cv::Vec3f person = beam(2, 4, 5.f);
  cleaner.map(mc::test::tinyFrame({{{2, 4}, person}}), kAllStatic, kOrigin);  // its own hit
  cleaner.map(frameAt(10.f), kAllStatic, kOrigin);  // then the place is empty: seen through
  cleaner.map(frameAt(10.f), kAllStatic, kOrigin);
  const std::size_t mapped = cleaner.staticMap().size();
  cleaner.finish();
  EXPECT_EQ(cleaner.voted(), 0u);
  EXPECT_EQ(cleaner.seenThrough(), 1u);
  const mc::MapCollector& map = cleaner.collected();
  ASSERT_EQ(map.dynamic_points.size(), 1u);
  EXPECT_NEAR(map.dynamic_points[0].x, person[0], 1e-5);
  EXPECT_NEAR(map.dynamic_points[0].z, person[2], 1e-5);
  EXPECT_EQ(map.static_points.size(), mapped - 1);  // the walls at 10 m stay
}

dynobj::core::LidarFrame at(dynobj::core::LidarFrame f, double seconds) {
  f.timestamp_ns = static_cast<std::int64_t>(seconds * 1e9);
  return f;
}

TEST(MapCleaner, TheScansOfThePastSecondsCountForANewVoxel) {
  // One pass: a scan counts against the map as it is then; a voxel new in the map takes the views
  // of the scans of the last free_space_past seconds (the place seen empty before someone came).
  mc::MapCleaner cleaner = streamingCleaner();  // free_space_past 30 s
  cleaner.map(at(frameAt(10.f), 0.0), kAllStatic, kOrigin);
  cleaner.map(at(frameAt(10.f), 1.0), kAllStatic, kOrigin);
  const std::size_t before = cleaner.staticMap().size();
  cleaner.map(at(mc::test::tinyFrame({{{2, 4}, beam(2, 4, 5.f)}}), 2.0), kAllStatic, kOrigin);
  EXPECT_EQ(cleaner.staticMap().size(), before + 1);
  cleaner.finish();
  EXPECT_EQ(cleaner.seenThrough(), 1u);
  EXPECT_EQ(cleaner.collected().dynamic_points.size(), 1u);
}

TEST(MapCleaner, ScansOlderThanThePastWindowAreForgotten) {
  mc::MapCleanParams p;
  p.voxel_size = 1.0;
  p.visibility = params();
  p.visibility.past = 1.5;
  p.free_space_stride = 1;
  mc::MapCleaner cleaner(p);
  cleaner.map(at(frameAt(10.f), 0.0), kAllStatic, kOrigin);  // 2 s before the person: forgotten
  cleaner.map(at(frameAt(10.f), 1.0), kAllStatic, kOrigin);  // 1 s before: one view, < min_views
  cleaner.map(at(mc::test::tinyFrame({{{2, 4}, beam(2, 4, 5.f)}}), 2.0), kAllStatic, kOrigin);
  cleaner.finish();
  EXPECT_EQ(cleaner.seenThrough(), 0u);
  p.visibility.past = 0;  // none remembered
  mc::MapCleaner none(p);
  none.map(at(frameAt(10.f), 1.0), kAllStatic, kOrigin);
  none.map(at(frameAt(10.f), 1.5), kAllStatic, kOrigin);
  none.map(at(mc::test::tinyFrame({{{2, 4}, beam(2, 4, 5.f)}}), 2.0), kAllStatic, kOrigin);
  none.finish();
  EXPECT_EQ(none.seenThrough(), 0u);
}

TEST(MapCleaner, AScanLookedAtCountsItsViewsButMapsNothing) {
  // A chunk's overlap (look): before its range, the views of the past; after it, later views.
  mc::MapCleaner cleaner = streamingCleaner();
  cleaner.look(at(frameAt(10.f), 0.0), kOrigin);  // before: the place seen empty
  cleaner.look(at(frameAt(10.f), 1.0), kOrigin);
  EXPECT_TRUE(cleaner.staticMap().empty());  // looked at, not mapped
  cleaner.map(at(mc::test::tinyFrame({{{2, 4}, beam(2, 4, 5.f)}}), 2.0), kAllStatic, kOrigin);
  EXPECT_EQ(cleaner.staticMap().size(), 1u);
  cleaner.finish();
  EXPECT_EQ(cleaner.seenThrough(), 1u);  // the two looks before count as past views

  mc::MapCleaner later = streamingCleaner();
  later.map(at(mc::test::tinyFrame({{{2, 4}, beam(2, 4, 5.f)}}), 0.0), kAllStatic, kOrigin);
  later.look(at(frameAt(10.f), 1.0), kOrigin);  // after: seen through twice
  later.look(at(frameAt(10.f), 2.0), kOrigin);
  EXPECT_EQ(later.staticMap().size(), 1u);
  later.finish();
  EXPECT_EQ(later.seenThrough(), 1u);
}

TEST(MapCleaner, AVoxelNoPointFellIntoForFinalAfterIsDecidedAndLeavesMemory) {
  // A person at 5 m (one voxel), then the walls at 10 m seen through their place, scan after scan:
  // final_after 2 s after the person's last point, their voxel is decided (seen through: dynamic)
  // and written; the walls, hit by every scan, stay in memory until finish().
  mc::MapCleanParams p;
  p.voxel_size = 1.0;
  p.visibility = params();
  p.free_space_stride = 1;
  p.final_after = 2.0;
  mc::MapCleaner cleaner(p);
  cleaner.map(at(mc::test::tinyFrame({{{2, 4}, beam(2, 4, 5.f)}}), 0.0), kAllStatic, kOrigin);
  const std::size_t walls = [] {
    mc::MapCleanParams q;
    q.voxel_size = 1.0;
    mc::MapCleaner c(q);
    c.map(frameAt(10.f), kAllStatic, kOrigin);
    return c.staticMap().size();
  }();
  for (int k = 1; k <= 4; k++) {
    cleaner.map(at(frameAt(10.f), 0.5 * k), kAllStatic, kOrigin);
    EXPECT_TRUE(cleaner.collected().dynamic_points.empty()) << "at " << 0.5 * k << " s";
  }
  cleaner.map(at(frameAt(10.f), 2.5), kAllStatic, kOrigin);  // 2.5 s after the person's point
  ASSERT_EQ(cleaner.collected().dynamic_points.size(), 1u);
  EXPECT_EQ(cleaner.seenThrough(), 1u);
  EXPECT_EQ(cleaner.staticMap().size(), walls);  // the person's voxel left memory
  EXPECT_TRUE(cleaner.collected().static_points.empty());
  cleaner.finish();
  EXPECT_EQ(cleaner.collected().static_points.size(), walls);

  p.final_after = 0;  // off: everything waits for finish()
  mc::MapCleaner whole(p);
  whole.map(at(mc::test::tinyFrame({{{2, 4}, beam(2, 4, 5.f)}}), 0.0), kAllStatic, kOrigin);
  for (int k = 1; k <= 5; k++) whole.map(at(frameAt(10.f), 0.5 * k), kAllStatic, kOrigin);
  EXPECT_TRUE(whole.collected().dynamic_points.empty());
  EXPECT_EQ(whole.staticMap().size(), walls + 1);
}
