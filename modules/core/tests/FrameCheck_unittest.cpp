// SPDX-License-Identifier: BSD-3-Clause
// FrameCheck: each fault of the data on tiny hand-made sweeps (4 x 8 pixels, 10 Hz), with the
// warning's sweep number, figure and the verdict; clean sweeps give none.
#include <dynobj/core/Config.h>
#include <dynobj/core/FrameCheck.h>
#include <gtest/gtest.h>

using namespace dynobj::core;

namespace {

constexpr std::int64_t kT0 = 1000000000LL;  // [ns]
constexpr std::int64_t kPeriod = 100000000LL;

/// A 4 x 8 sweep at `stamp`: every pixel a return at 5 m + `shift` (+ a little per pixel), with
/// intensity 10, one input point per pixel.
LidarFrame sweep(std::int64_t stamp, float shift = 0) {
  SensorModel s;
  s.rows = 4;
  s.cols = 8;
  s.frequency = 10;
  LidarFrame f(s);
  for (int r = 0; r < 4; r++)
    for (int c = 0; c < 8; c++) {
      const float range = 5.f + shift + 0.01f * static_cast<float>(r * 8 + c);
      f.setPixel(r, c, range, 10.f, cv::Vec3f(range, 0, 0), r * 8 + c);
      f.point_pixel.push_back(r * 8 + c);
    }
  f.has_intensity = true;
  f.timestamp_ns = stamp;
  return f;
}

struct Checked {
  FrameCheck::Verdict verdict;
  std::vector<FrameWarning> warnings;
};

/// Removes the returns of `columns` (and their input points, as a sweep without them).
void emptyColumns(LidarFrame& f, std::initializer_list<int> columns) {
  for (int c : columns)
    for (int r = 0; r < f.rows(); r++) f.clearPixel(r, c);
  f.point_pixel.clear();
  for (int px = 0; px < f.rows() * f.cols(); px++)
    if (f.isValid(px / f.cols(), px % f.cols())) f.point_pixel.push_back(px);
}

Checked run(FrameCheck& check, const LidarFrame& f, long sweep_number) {
  Checked c;
  c.verdict = check.check(f, sweep_number, c.warnings);
  return c;
}

}  // namespace

TEST(FrameCheck, CleanSweepsGiveNoWarning) {
  FrameCheck check;
  for (long k = 0; k < 5; k++) {
    const Checked c = run(check, sweep(kT0 + k * kPeriod, 0.05f * static_cast<float>(k)), k);
    EXPECT_EQ(c.verdict, FrameCheck::Verdict::Use) << "sweep " << k;
    EXPECT_TRUE(c.warnings.empty()) << c.warnings.front().text();
  }
}

TEST(FrameCheck, TimeReversalIsSkippedAndTheNextSweepComparedWithTheLastUsed) {
  FrameCheck check;
  run(check, sweep(kT0), 0);
  run(check, sweep(kT0 + kPeriod, 0.1f), 1);
  const Checked back = run(check, sweep(kT0 + kPeriod / 2, 0.2f), 2);
  EXPECT_EQ(back.verdict, FrameCheck::Verdict::Skip);
  ASSERT_EQ(back.warnings.size(), 1u);
  EXPECT_EQ(back.warnings[0].fault, FrameFault::TimeReversal);
  EXPECT_EQ(back.warnings[0].sweep, 2);
  EXPECT_NEAR(back.warnings[0].figure, 0.05, 1e-9);
  EXPECT_EQ(back.warnings[0].text(),
            "sweep 2: time went back 0.050 s: the sweep is not used for tracking");
  // The next sweep, one period after sweep 1: clean (not a 0.15 s gap after the skipped one).
  const Checked next = run(check, sweep(kT0 + 2 * kPeriod, 0.3f), 3);
  EXPECT_EQ(next.verdict, FrameCheck::Verdict::Use);
  EXPECT_TRUE(next.warnings.empty());
}

TEST(FrameCheck, DuplicatesAreSkipped) {
  FrameCheck check;
  run(check, sweep(kT0), 0);
  const Checked same_time = run(check, sweep(kT0, 0.1f), 1);
  EXPECT_EQ(same_time.verdict, FrameCheck::Verdict::Skip);
  ASSERT_EQ(same_time.warnings.size(), 1u);
  EXPECT_EQ(same_time.warnings[0].fault, FrameFault::DuplicateTime);
  const Checked same_ranges = run(check, sweep(kT0 + kPeriod), 2);  // new time, same ranges
  EXPECT_EQ(same_ranges.verdict, FrameCheck::Verdict::Skip);
  ASSERT_EQ(same_ranges.warnings.size(), 1u);
  EXPECT_EQ(same_ranges.warnings[0].fault, FrameFault::DuplicateContent);
  EXPECT_EQ(same_ranges.warnings[0].sweep, 2);
}

TEST(FrameCheck, AStaleSensorIsSkippedSweepBySweepNotTakenForATimeJump) {
  FrameCheck check;  // the same ranges for 2 s, stamped every period: each one a duplicate
  run(check, sweep(kT0), 0);
  for (long k = 1; k <= 20; k++) {
    const Checked c = run(check, sweep(kT0 + k * kPeriod), k);
    EXPECT_EQ(c.verdict, FrameCheck::Verdict::Skip) << "sweep " << k;
    ASSERT_EQ(c.warnings.size(), 1u);
    EXPECT_EQ(c.warnings[0].fault, FrameFault::DuplicateContent);
  }
  const Checked back = run(check, sweep(kT0 + 21 * kPeriod, 0.1f), 21);
  EXPECT_EQ(back.verdict, FrameCheck::Verdict::Use);
  EXPECT_TRUE(back.warnings.empty());
}

TEST(FrameCheck, MissingSweepsWarnAndATimeJumpRestarts) {
  FrameCheck check;  // max_gap 1 s
  run(check, sweep(kT0), 0);
  const Checked gap = run(check, sweep(kT0 + 3 * kPeriod, 0.1f), 1);  // 0.3 s: 2 sweeps missing
  EXPECT_EQ(gap.verdict, FrameCheck::Verdict::Use);
  ASSERT_EQ(gap.warnings.size(), 1u);
  EXPECT_EQ(gap.warnings[0].fault, FrameFault::MissingSweeps);
  EXPECT_NEAR(gap.warnings[0].figure, 0.3, 1e-9);
  EXPECT_NE(gap.warnings[0].message.find("about 2 sweeps"), std::string::npos)
      << gap.warnings[0].message;
  const Checked one_and_a_bit = run(check, sweep(kT0 + 4 * kPeriod + kPeriod / 4, 0.2f), 2);
  EXPECT_TRUE(one_and_a_bit.warnings.empty());  // 1.25 periods: jitter, not a missing sweep
  const Checked jump = run(check, sweep(kT0 + 20 * kPeriod, 0.3f), 3);  // 1.575 s
  EXPECT_EQ(jump.verdict, FrameCheck::Verdict::Restart);
  ASSERT_EQ(jump.warnings.size(), 1u);
  EXPECT_EQ(jump.warnings[0].fault, FrameFault::TimeJump);
  EXPECT_NEAR(jump.warnings[0].figure, 1.575, 1e-9);
}

TEST(FrameCheck, ClockStepsBackMoreThanMaxGapRestarts) {
  FrameCheck check;  // max_gap 1 s: a recording replayed from its start is not skipped forever
  run(check, sweep(kT0 + 40 * kPeriod), 0);
  const Checked back = run(check, sweep(kT0, 0.1f), 1);
  EXPECT_EQ(back.verdict, FrameCheck::Verdict::Restart);
  ASSERT_EQ(back.warnings.size(), 1u);
  EXPECT_EQ(back.warnings[0].fault, FrameFault::TimeJump);
  EXPECT_NEAR(back.warnings[0].figure, -4.0, 1e-9);
  EXPECT_EQ(back.warnings[0].text(),
            "sweep 1: time went back 4.000 s (more than max_gap 1.000 s): the tracks and the "
            "motion history start anew");
  EXPECT_TRUE(run(check, sweep(kT0 + kPeriod, 0.2f), 2).warnings.empty());  // runs on from there
}

TEST(FrameCheck, UnstampedSweepsAreNotTimed) {
  FrameCheck check;
  run(check, sweep(0), 0);
  const Checked c = run(check, sweep(0, 0.1f), 1);
  EXPECT_EQ(c.verdict, FrameCheck::Verdict::Use);
  EXPECT_TRUE(c.warnings.empty());
}

TEST(FrameCheck, LostColumnsNameTheShareAndTheWidestGap) {
  FrameCheck check;  // max_lost_columns 0.25
  run(check, sweep(kT0), 0);
  LidarFrame partial = sweep(kT0 + kPeriod, 0.1f);
  emptyColumns(partial, {4, 5, 6, 7});  // the last half of the revolution
  const Checked c = run(check, partial, 1);
  EXPECT_EQ(c.verdict, FrameCheck::Verdict::Use);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].fault, FrameFault::LostColumns);
  EXPECT_DOUBLE_EQ(c.warnings[0].figure, 0.5);
  EXPECT_NE(c.warnings[0].message.find("50 % of the columns"), std::string::npos);
  EXPECT_NE(c.warnings[0].message.find("widest gap 180 deg"), std::string::npos)
      << c.warnings[0].message;
  // Two columns of eight (25 %) are not more than max_lost_columns.
  FrameCheck check2;
  run(check2, sweep(kT0), 0);
  LidarFrame quarter = sweep(kT0 + kPeriod, 0.1f);
  emptyColumns(quarter, {0, 7});
  EXPECT_TRUE(run(check2, quarter, 1).warnings.empty());
}

TEST(FrameCheck, WideSweepFromMorePointsPerPixel) {
  FrameCheck check;
  run(check, sweep(kT0), 0);
  LidarFrame wide = sweep(kT0 + kPeriod, 0.1f);
  for (int px = 0; px < 8; px++) wide.point_pixel.push_back(px);  // 40 points on 32 pixels
  const Checked c = run(check, wide, 1);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].fault, FrameFault::WideSweep);
  EXPECT_NEAR(c.warnings[0].figure, 90.0, 1e-9);  // a quarter more: 90 degrees twice
}

TEST(FrameCheck, ZeroIntensityAfterIntensity) {
  FrameCheck check;
  run(check, sweep(kT0), 0);
  LidarFrame dark = sweep(kT0 + kPeriod, 0.1f);
  dark.intensity.setTo(0);
  const Checked c = run(check, dark, 1);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0].fault, FrameFault::ZeroIntensity);
  dark.timestamp_ns += kPeriod;
  dark.range += 0.1f;
  EXPECT_TRUE(run(check, dark, 2).warnings.empty());   // once, where it starts
  LidarFrame no_channel = sweep(kT0 + kPeriod, 0.3f);  // a source without intensity
  no_channel.intensity.setTo(0);
  no_channel.has_intensity = false;
  FrameCheck check2;
  run(check2, sweep(kT0), 0);
  EXPECT_TRUE(run(check2, no_channel, 1).warnings.empty());
}

TEST(FrameCheck, EgoMotionFailuresWarnOncePerRun) {
  FrameCheckParams p;
  p.max_ego_failures = 3;
  FrameCheck check(p);
  std::vector<FrameWarning> w;
  for (long k = 0; k < 5; k++) check.egoMotion(false, k, w);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].fault, FrameFault::EgoMotionFailures);
  EXPECT_EQ(w[0].sweep, 2);  // the third failure in a row
  EXPECT_DOUBLE_EQ(w[0].figure, 3.0);
  check.egoMotion(true, 5, w);
  for (long k = 6; k < 8; k++) check.egoMotion(false, k, w);
  EXPECT_EQ(w.size(), 1u);  // two failures after a success: no new run of three
}

TEST(FrameCheck, ValidateNamesTheBadKey) {
  FrameCheckParams p;
  p.max_gap = 0;
  EXPECT_THROW(
      {
        try {
          p.validate();
        } catch (const ParameterError& e) {
          EXPECT_NE(std::string(e.what()).find("max_gap"), std::string::npos) << e.what();
          throw;
        }
      },
      ParameterError);
  p = FrameCheckParams{};
  p.max_lost_columns = 1.5;
  EXPECT_THROW(FrameCheck{p}, ParameterError);
  p = FrameCheckParams{};
  p.max_ego_failures = 0;
  try {
    p.validate();
    ADD_FAILURE() << "max_ego_failures = 0 accepted";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("max_ego_failures"), std::string::npos) << e.what();
  }
}
