// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Config.h>
#include <dynobj/mapclean/MapCleaner.h>
#include <gtest/gtest.h>

#include "FrameFixture.h"

namespace mc = dynobj::mapclean;
using dynobj::core::DetectionResult;
using dynobj::core::TrackedObject;

namespace {

DetectionResult result(std::int64_t t, std::vector<int> dynamic_pixels,
                       std::vector<TrackedObject> objects) {
  DetectionResult r;
  r.timestamp_ns = t;
  r.dynamic = cv::Mat_<std::uint8_t>(4, 8, std::uint8_t{0});
  for (int px : dynamic_pixels) r.dynamic(px / 8, px % 8) = 255;
  r.objects = std::move(objects);
  return r;
}

TrackedObject object(int id, bool dynamic, Eigen::Vector3d lo, Eigen::Vector3d hi) {
  TrackedObject o;
  o.id = id;
  o.dynamic = dynamic;
  o.box_min = lo;
  o.box_max = hi;
  return o;
}

mc::MapCleanParams params(double voxel) {
  mc::MapCleanParams p;
  p.voxel_size = voxel;
  p.box_margin = 0.1;
  return p;
}

}  // namespace

TEST(MapCleaner, BackfillMarksATracksFramesBeforeItWasConfirmed) {
  mc::MapCleaner cleaner(params(0.0));
  // Frame 0: track 7 seen at x = 5 (not yet dynamic); the detector flags nothing.
  // Frame 1: track 7 confirmed dynamic (pixel 9 flagged); track 8 never dynamic.
  const auto rec0 = cleaner.record(result(0, {},
                                          {object(7, false, {4.8, -0.2, -0.5}, {5.2, 0.2, 1.0}),
                                           object(8, false, {9, 9, 0}, {10, 10, 1})}),
                                   Eigen::Isometry3d::Identity());
  const auto rec1 =
      cleaner.record(result(100, {9}, {object(7, true, {5.8, -0.2, -0.5}, {6.2, 0.2, 1.0})}),
                     Eigen::Isometry3d::Identity());
  EXPECT_EQ(cleaner.confirmedTracks(), (std::set<int>{7}));
  const auto f0 = mc::test::tinyFrame({{{1, 2}, {5.0f, 0.1f, 0.5f}},  // in track 7's box
                                       {{1, 3}, {5.25f, 0.f, 0.f}},   // within the 0.1 m margin
                                       {{2, 3}, {5.0f, 0.f, -0.6f}},  // below the box: floor, kept
                                       {{1, 4}, {9.5f, 9.5f, 0.5f}},  // track 8: never dynamic
                                       {{0, 0}, {1.f, 1.f, 1.f}}});
  const auto with = cleaner.dynamicMask(f0, rec0);
  EXPECT_EQ(with(1, 2), 255);
  EXPECT_EQ(with(1, 3), 255);
  EXPECT_EQ(with(2, 3), 0);
  EXPECT_EQ(with(1, 4), 0);
  EXPECT_EQ(with(0, 0), 0);
  EXPECT_EQ(cleaner.backfilledPixels(), 2u);
  mc::MapCleanParams causal = params(0.0);
  causal.backfill_window = 0;  // no back-fill: only the detector's pixels
  const mc::MapCleaner online(causal);
  EXPECT_EQ(cv::countNonZero(online.dynamicMask(f0, rec0)), 0);
  // Frame 1: the detector's own pixel is kept as is.
  const auto f1 = mc::test::tinyFrame({{{1, 1}, {6.f, 0.f, 0.f}}});
  EXPECT_EQ(online.dynamicMask(f1, rec1)(1, 1), 255);
}

TEST(MapCleaner, AccumulatesIntoStaticAndDynamicMapsInTheWorld) {
  mc::MapCleaner cleaner(params(1.0));
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(10, 0, 0);
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const auto f = mc::test::tinyFrame({{{1, 1}, {2.5f, 0.5f, 0.5f}},
                                      {{1, 2}, {2.5f, 0.7f, 0.5f}},  // one voxel
                                      {{2, 2}, {5.5f, 0.5f, 0.5f}}});
  cv::Mat_<std::uint8_t> mask(4, 8, std::uint8_t{0});
  mask(2, 2) = 255;
  cleaner.map(f, mask, pose);
  cleaner.map(f, mask, pose);  // the same scan twice: the maps do not grow
  ASSERT_EQ(cleaner.staticMap().size(), 1u);
  ASSERT_EQ(cleaner.dynamicMap().size(), 1u);
  EXPECT_EQ(cleaner.staticMap().pointsInserted(), 4u);
  const auto s = cleaner.staticMap().points()[0];
  EXPECT_NEAR(s.x, 10 - 0.6, 1e-5);  // rotated by 90 deg: (x, y) -> (-y, x), then shifted
  EXPECT_NEAR(s.y, 2.5, 1e-5);
  EXPECT_NEAR(s.intensity, 5.0, 1e-5);
  const auto d = cleaner.dynamicMap().points()[0];
  EXPECT_NEAR(d.y, 5.5, 1e-5);
}

TEST(MapCleaner, MinRangeDropsNearPointsFromBothMaps) {
  auto p = params(0.0);
  p.min_range = 1.0;
  mc::MapCleaner cleaner(p);
  const auto f = mc::test::tinyFrame({{{1, 1}, {0.5f, 0.f, 0.f}}, {{1, 2}, {2.f, 0.f, 0.f}}});
  cleaner.map(f, cv::Mat_<std::uint8_t>(4, 8, std::uint8_t{0}), Eigen::Isometry3d::Identity());
  EXPECT_EQ(cleaner.staticMap().size(), 1u);
}

TEST(MapCleaner, BadParametersNameTheKey) {
  auto p = params(-1);
  try {
    mc::MapCleaner c(p);
    FAIL();
  } catch (const dynobj::core::ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("voxel_size"), std::string::npos);
  }
}

TEST(MapCleaner, VoxelVoteMovesMostlyDynamicVoxels) {
  mc::MapCleaner cleaner(params(1.0));  // dynamic_vote = 1
  // Voxel A: 1 static + 2 dynamic points -> moves; voxel B: 2 static + 1 dynamic -> stays.
  const auto f = mc::test::tinyFrame({{{0, 0}, {0.5f, 0.5f, 0.5f}},
                                      {{0, 1}, {0.6f, 0.5f, 0.5f}},
                                      {{0, 2}, {0.7f, 0.5f, 0.5f}},
                                      {{1, 0}, {3.5f, 0.5f, 0.5f}},
                                      {{1, 1}, {3.6f, 0.5f, 0.5f}},
                                      {{1, 2}, {3.7f, 0.5f, 0.5f}}});
  cv::Mat_<std::uint8_t> mask(4, 8, std::uint8_t{0});
  mask(0, 1) = mask(0, 2) = mask(1, 2) = 255;
  cleaner.map(f, mask, Eigen::Isometry3d::Identity());
  cleaner.finish();
  EXPECT_EQ(cleaner.voted(), 1u);
  const mc::MapCollector& map = cleaner.collected();
  ASSERT_EQ(map.static_points.size(), 1u);
  EXPECT_NEAR(map.static_points[0].x, 3.55, 1e-5);  // only B's static points
  ASSERT_EQ(map.dynamic_points.size(), 2u);
  EXPECT_NEAR(map.dynamic_points[0].x, 0.6, 1e-5);  // A: all three points
  EXPECT_TRUE(cleaner.staticMap().empty());         // every voxel final, none left in memory
  EXPECT_TRUE(cleaner.dynamicMap().empty());
}
