// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/GroundSegmenter.h>
#include <dynobj/core/RegionGrower.h>
#include <gtest/gtest.h>

#include <cmath>

#include "SyntheticScene.h"

using namespace dynobj::core;
using dynobj::test::Scene;

TEST(RegionGrower, FillsTheObjectAndStopsAtGroundAndDepthJumps) {
  Scene scene;
  scene.posts.push_back({4, 0, 0.3, 1.8});    // the object
  scene.posts.push_back({4, 1.2, 0.3, 1.8});  // a neighbour 1.2 m away: a depth/space jump
  const auto s = dynobj::test::smallSensor();
  const LidarFrame f = dynobj::test::render(scene, s);
  cv::Mat_<std::uint8_t> ground;
  GroundSegmenter().segment(f, ground);
  // Ground truth: pixels whose point lies on the first post.
  auto onPost = [&](int r, int c, double px, double py) {
    const cv::Vec3f& p = f.xyz(r, c);
    return std::abs(std::hypot(p[0] - px, p[1] - py) - 0.3) < 1e-3 && p[2] > -1.0f + 0.04f;
  };
  int seed = -1, truth = 0;
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++)
      if (f.isValid(r, c) && onPost(r, c, 4, 0)) {
        truth++;
        if (seed < 0) seed = r * f.cols() + c;
      }
  ASSERT_GT(truth, 4);
  cv::Mat_<std::uint8_t> mask;
  cv::Mat_<int> owner;
  const auto counts = RegionGrower().grow(f, ground, {{seed}}, mask, owner);
  EXPECT_EQ(counts[0], truth);
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++)
      EXPECT_EQ(mask(r, c) != 0, f.isValid(r, c) && onPost(r, c, 4, 0)) << r << "," << c;
}

TEST(RegionGrower, WrapsAroundTheSeamAndRespectsMaxExtent) {
  Scene scene;
  scene.posts.push_back({-4, 0, 0.4, 1.5});  // straight behind: spans the column seam
  const auto s = dynobj::test::smallSensor();
  const LidarFrame f = dynobj::test::render(scene, s);
  cv::Mat_<std::uint8_t> ground, mask;
  cv::Mat_<int> owner;
  GroundSegmenter().segment(f, ground);
  const int r = 8;  // just below the horizon, hits the post
  ASSERT_TRUE(f.isValid(r, 0));
  ASSERT_LT(f.range(r, 0), 4.0f);
  RegionGrower().grow(f, ground, {{r * f.cols() + 0}}, mask, owner);
  EXPECT_TRUE(mask(r, f.cols() - 1));  // reached across the seam
  RegionGrowingParams tight;
  tight.max_extent = 0.05;
  cv::Mat_<std::uint8_t> m2;
  cv::Mat_<int> o2;
  const auto n = RegionGrower(tight).grow(f, ground, {{r * f.cols() + 0}}, m2, o2);
  EXPECT_LT(n[0], cv::countNonZero(mask));
}

namespace {

/// Two posts touching (centres 0.6 m apart, radius 0.3) 4 m ahead: the frame, its ground and each
/// post's pixels.
struct TwoPosts {
  LidarFrame f;
  cv::Mat_<std::uint8_t> ground;
  std::vector<int> first, second;
  TwoPosts() {
    Scene scene;
    scene.posts.push_back({4, 0, 0.3, 1.8});
    scene.posts.push_back({4, 0.6, 0.3, 1.8});
    f = dynobj::test::render(scene, dynobj::test::smallSensor(16, 720));
    GroundSegmenter().segment(f, ground);
    for (int r = 0; r < f.rows(); r++)
      for (int c = 0; c < f.cols(); c++) {
        if (!f.isValid(r, c) || ground(r, c) || f.range(r, c) > 6) continue;
        (f.xyz(r, c)[1] < 0.3f ? first : second).push_back(r * f.cols() + c);
      }
  }
};

}  // namespace

TEST(RegionGrower, DoesNotTakePixelsKeptOut) {
  // Two posts touching (centres 0.6 m apart, radius 0.3): grown from the first, the region takes
  // the second too; with the second's pixels kept out (an object known to stand still), it
  // stops at them, and they stay kept out, in nobody's mask.
  const TwoPosts t;
  const LidarFrame& f = t.f;
  const cv::Mat_<std::uint8_t>& ground = t.ground;
  const std::vector<int>&first = t.first, &second = t.second;
  ASSERT_GT(first.size(), 4u);
  ASSERT_GT(second.size(), 4u);
  cv::Mat_<std::uint8_t> mask;
  cv::Mat_<int> owner;
  RegionGrower().grow(f, ground, {{first[0]}}, mask, owner);
  const auto taken = [&](const std::vector<int>& px) {
    std::size_t n = 0;
    for (int p : px) n += mask(p / f.cols(), p % f.cols()) ? 1 : 0;
    return n;
  };
  ASSERT_EQ(taken(second), second.size());  // one surface: all of it without the keep-out
  cv::Mat_<std::uint8_t> mask2;
  cv::Mat_<int> owner2(f.rows(), f.cols(), RegionGrower::kFree);
  RegionGrower::keepOut(second, owner2);
  const auto counts = RegionGrower().grow(f, ground, {{first[0]}}, mask2, owner2);
  mask = mask2;
  EXPECT_EQ(taken(first), first.size());
  EXPECT_EQ(taken(second), 0u);
  EXPECT_EQ(counts[0], static_cast<int>(first.size()));
  for (int p : second) EXPECT_EQ(owner2(p / f.cols(), p % f.cols()), RegionGrower::kKeptOut);
}

TEST(RegionGrower, AnAdmissionTestKeepsRefusedPixelsOutOfEveryRegion) {
  // The two touching posts again: grown from the first with a test that refuses the second's
  // pixels (past_surface_check: points seen on a surface before the mover came), the region stops
  // at them, they are kept out and listed in refused(); the test is never asked about a seed.
  const TwoPosts t;
  const int W = t.f.cols();
  ASSERT_GT(t.second.size(), 4u);
  std::vector<char> on_second(t.f.range.total(), 0);
  for (int p : t.second) on_second[static_cast<std::size_t>(p)] = 1;
  int asked_about_seed = 0;
  const RegionGrower::Admit admit = [&](std::size_t obj, int px) {
    EXPECT_EQ(obj, 0u);
    asked_about_seed += px == t.first[0] ? 1 : 0;
    return !on_second[static_cast<std::size_t>(px)];
  };
  cv::Mat_<std::uint8_t> mask;
  cv::Mat_<int> owner;
  RegionGrower grower;
  const auto counts = grower.grow(t.f, t.ground, {{t.first[0]}}, mask, owner, admit);
  EXPECT_EQ(counts[0], static_cast<int>(t.first.size()));
  EXPECT_EQ(asked_about_seed, 0);
  std::size_t taken = 0;
  for (int p : t.second) taken += mask(p / W, p % W) ? 1 : 0;
  EXPECT_EQ(taken, 0u);
  EXPECT_FALSE(grower.refused().empty());
  for (int p : grower.refused()) {
    EXPECT_TRUE(on_second[static_cast<std::size_t>(p)]);
    EXPECT_EQ(owner(p / W, p % W), RegionGrower::kKeptOut);
  }
  // Without the test the region takes both posts, and nothing is refused.
  cv::Mat_<std::uint8_t> mask2;
  cv::Mat_<int> owner2;
  EXPECT_EQ(grower.grow(t.f, t.ground, {{t.first[0]}}, mask2, owner2)[0],
            static_cast<int>(t.first.size() + t.second.size()));
  EXPECT_TRUE(grower.refused().empty());
}

TEST(RegionGrower, NearerOwnSeedsKeepsTheBodyOfOneAtRestBesideTheMover) {
  // The two touching posts, their pixels of even rows the features (the first a mover's seeds,
  // the second's those of one standing, kept out). The keep-out alone holds the second's
  // features only, and the region takes the rest of that body; refusing what lies nearer to its
  // features than to the mover's own (within 0.5 m) holds all of it, and takes all of the first.
  const TwoPosts t;
  const int W = t.f.cols();
  std::vector<int> seeds, beside;
  for (int p : t.first)
    if ((p / W) % 2 == 0) seeds.push_back(p);
  for (int p : t.second)
    if ((p / W) % 2 == 0) beside.push_back(p);
  ASSERT_GT(seeds.size(), 4u);
  ASSERT_GT(beside.size(), 4u);
  auto grow = [&](const RegionGrower::Admit& admit) {
    cv::Mat_<std::uint8_t> mask;
    cv::Mat_<int> owner(t.f.rows(), t.f.cols(), RegionGrower::kFree);
    RegionGrower::keepOut(beside, owner);
    RegionGrower().grow(t.f, t.ground, {seeds}, mask, owner, admit);
    std::pair<std::size_t, std::size_t> taken{0, 0};
    for (int p : t.first) taken.first += mask(p / W, p % W) ? 1 : 0;
    for (int p : t.second) taken.second += mask(p / W, p % W) ? 1 : 0;
    return taken;
  };
  const auto alone = grow({});
  EXPECT_EQ(alone.first, t.first.size());
  EXPECT_GT(alone.second, 0u);
  const auto held = grow(RegionGrower::nearerOwnSeeds(t.f, {seeds}, {beside}, 0.5, {}));
  EXPECT_EQ(held.first, t.first.size());
  EXPECT_EQ(held.second, 0u);
  // Nothing beside it: no test at all; and what `then` refuses stays refused.
  EXPECT_FALSE(RegionGrower::nearerOwnSeeds(t.f, {seeds}, {{}}, 0.5, {}));
  const RegionGrower::Admit none = [](std::size_t, int) { return false; };
  const auto nothing = grow(RegionGrower::nearerOwnSeeds(t.f, {seeds}, {beside}, 0.5, none));
  EXPECT_EQ(nothing.first, seeds.size());
  EXPECT_EQ(nothing.second, 0u);
}

TEST(RegionGrower, JoinsATopSetBackOnlyAboveAndWithinTheSlope) {
  RegionGrowingParams p;      // distance 0.25, range_factor 1.2, depth_factor 0.02, slope_factor 3
  const double gap = 0.0245;  // 1.4 deg between rows (OS0-64) ...
  const double r = 12.8, e = -0.05;  // ... a car's boot 12.8 m ahead, its cabin 0.7 m behind
  auto at = [](double range, double elevation) {
    return cv::Vec3f(static_cast<float>(range * std::cos(elevation)), 0.f,
                     static_cast<float>(range * std::sin(elevation)));
  };
  const cv::Vec3f boot = at(r, e), cabin = at(r + 0.7, e + gap);
  // 0.7 m is beyond distance + depth_factor x range (0.506 m), within 3 x 12.8 x 0.0245 (0.94 m).
  EXPECT_TRUE(p.joins(boot, r, cabin, r + 0.7, gap, true));
  EXPECT_FALSE(p.joins(boot, r, cabin, r + 0.7, gap, false));  // not the pixel above
  EXPECT_FALSE(p.joins(cabin, r + 0.7, boot, r, gap, true));   // nearer above: an overhang
  const cv::Vec3f wall = at(r + 1.0, e + gap);                 // beyond 0.94 m
  EXPECT_FALSE(p.joins(boot, r, wall, r + 1.0, gap, true));
  p.slope_factor = 0;
  EXPECT_FALSE(p.joins(boot, r, cabin, r + 0.7, gap, true));
  // The usual test is unchanged: 0.4 m deeper is one surface either way.
  EXPECT_TRUE(p.joins(boot, r, at(r + 0.4, e + gap), r + 0.4, gap, false));
}

TEST(RegionGrower, TakesACabinSetBackAboveTheBootOfAWideObjectButNotTheWallBehind) {
  // Rows 1.875 deg apart: at 10 m the usual test allows a 0.45 m step, the slope 0.98 m.
  Scene scene;
  scene.room_radius = 20;
  scene.posts.push_back({10.6, 0, 0.6, 1.0});  // the boot: face at 10 m, top at sensor height
  scene.posts.push_back({11.4, 0, 0.6, 1.6});  // the cabin above it, its face 0.8 m farther
  const LidarFrame f = dynobj::test::render(scene, dynobj::test::smallSensor(16, 720));
  cv::Mat_<std::uint8_t> ground;
  GroundSegmenter().segment(f, ground);
  auto on = [&](int r, int c, double px, double height) {
    const cv::Vec3f& q = f.xyz(r, c);
    return f.isValid(r, c) && !ground(r, c) && std::abs(std::hypot(q[0] - px, q[1]) - 0.6) < 1e-3 &&
           q[2] < -1.0 + height + 1e-3;
  };
  std::vector<int> seeds;  // the whole boot, about 1 m wide
  int cabin = 0;
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++) {
      if (on(r, c, 10.6, 1.0)) seeds.push_back(r * f.cols() + c);
      cabin += on(r, c, 11.4, 1.6) ? 1 : 0;
    }
  const int boot = static_cast<int>(seeds.size());
  ASSERT_GT(boot, 4);
  ASSERT_GT(cabin, 4);
  RegionGrowingParams off, narrow;
  off.slope_factor = 0;
  narrow.set_back_radius = 1.0;  // as if the object were no wider than a person
  cv::Mat_<std::uint8_t> m0, m1, m3;
  cv::Mat_<int> o0, o1, o3;
  EXPECT_EQ(RegionGrower(off).grow(f, ground, {seeds}, m0, o0)[0], boot);
  EXPECT_EQ(RegionGrower(narrow).grow(f, ground, {seeds}, m1, o1)[0], boot);
  EXPECT_EQ(RegionGrower().grow(f, ground, {seeds}, m3, o3)[0], boot + cabin);
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++)
      EXPECT_EQ(m3(r, c) != 0, on(r, c, 10.6, 1.0) || on(r, c, 11.4, 1.6)) << r << "," << c;
}
