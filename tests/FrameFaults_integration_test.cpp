// SPDX-License-Identifier: BSD-3-Clause
// Faults of the data (core::FrameCheck) injected into a simulated sequence (the hall scenario,
// OS0-64 at 512 columns, 10 Hz): for each, the warning names the right sweep and figure, nothing
// throws, and the detector's per-sweep F1 against the simulator's truth is back to the clean run's
// within the number of sweeps docs/usage.md states ("Faults of the data").
#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/eval/Metrics.h>
#include <dynobj/sim/LidarSimulator.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>
#include <numeric>
#include <random>

using namespace dynobj;

namespace {

constexpr int kSweeps = 70;
constexpr int kFault = 30;       ///< the clean sweep where each fault starts
constexpr int kSpan = 15;        ///< sweeps after the recovery that must all be back
constexpr double kSlack = 0.05;  ///< F1 this far below the clean run's still counts as back
constexpr std::int64_t kPeriodNs = 100000000;

/// A sweep to give the detector: a frame and the clean sweep whose truth scores it (-1: none).
struct Feed {
  core::LidarFrame frame;
  int truth = -1;
};

struct Clean {
  std::vector<sim::SimulatedSweep> sweeps;
  std::vector<double> f1;  ///< per sweep, of the clean run
};

double f1Of(const cv::Mat_<std::uint8_t>& dynamic, const cv::Mat_<std::uint8_t>& truth,
            const cv::Mat_<std::uint8_t>& valid) {
  eval::Confusion c;
  c.add(dynamic, truth, valid);
  return c.f1().value_or(1.0);  // nothing to find and nothing flagged: right
}

struct FaultedRun {
  std::vector<core::FrameWarning> warnings;
  std::map<int, double> f1;  ///< by clean sweep index
  std::vector<char> ego_ok;  ///< per sweep given: the ego-motion estimated
};

FaultedRun run(const Clean& clean, const std::vector<Feed>& feed) {
  FaultedRun out;
  core::DynamicObjectDetector det;
  for (const Feed& f : feed) {
    const core::DetectionResult& r = det.process(f.frame);
    out.warnings.insert(out.warnings.end(), r.warnings.begin(), r.warnings.end());
    out.ego_ok.push_back(r.ego_motion.ok || out.ego_ok.empty());
    if (f.truth >= 0)
      out.f1[f.truth] =
          f1Of(r.dynamic, clean.sweeps[static_cast<std::size_t>(f.truth)].dynamic, f.frame.valid);
  }
  return out;
}

const Clean& clean() {
  static const Clean c = [] {
    Clean k;
    const sim::LidarSimulator simu(sim::Scenario::fromYamlFile(
        std::string(DYNOBJ_SHARE_DIR) + "/scenarios/hall.yaml", DYNOBJ_SHARE_DIR,
        {{"frames", std::to_string(kSweeps)}, {"sensor", "sensors/os0-64-512.ini"}}));
    for (int j = 0; j < kSweeps; j++) k.sweeps.push_back(simu.simulate(j));
    std::vector<Feed> feed;
    for (int j = 0; j < kSweeps; j++)
      feed.push_back({k.sweeps[static_cast<std::size_t>(j)].frame, j});
    const FaultedRun r = run(k, feed);
    for (int j = 0; j < kSweeps; j++) k.f1.push_back(r.f1.at(j));
    return k;
  }();
  return c;
}

/// The clean sequence with `change(j, feed)` deciding what is given for clean sweep j (append
/// nothing to drop it, more to insert).
std::vector<Feed> faulted(const std::function<void(int, std::vector<Feed>&)>& change) {
  std::vector<Feed> feed;
  for (int j = 0; j < kSweeps; j++) change(j, feed);
  return feed;
}

/// A copy of `f` that shares no pixel data with it (a fault changes the copy only).
core::LidarFrame deepCopy(const core::LidarFrame& f) {
  core::LidarFrame c = f;
  c.range = f.range.clone();
  c.intensity = f.intensity.clone();
  c.xyz = f.xyz.clone();
  c.valid = f.valid.clone();
  c.source_index = f.source_index.clone();
  return c;
}

/// Clean sweep j, scored against its truth.
Feed cleanFeed(int j) {
  return {deepCopy(clean().sweeps[static_cast<std::size_t>(j)].frame), j};
}

/// Sweeps after clean sweep `first` until the faulted run's F1 stays within kSlack of the clean
/// run's for kSpan sweeps; prints both series from there.
int recovery(const FaultedRun& r, int first, const char* what) {
  const Clean& c = clean();
  for (int n = 0; first + n + kSpan <= kSweeps; n++) {
    bool back = true;
    for (int j = first + n; j < first + n + kSpan && back; j++)
      back = r.f1.count(j) && r.f1.at(j) >= c.f1[static_cast<std::size_t>(j)] - kSlack;
    if (!back) continue;
    std::printf("%s: back to the clean F1 %d sweeps after sweep %d\n", what, n, first);
    return n;
  }
  std::printf("%s: not back within the sequence\n", what);
  for (int j = first; j < kSweeps; j++)
    std::printf("  sweep %d: clean F1 %.3f, faulted %.3f\n", j, c.f1[static_cast<std::size_t>(j)],
                r.f1.count(j) ? r.f1.at(j) : -1.0);
  return kSweeps;
}

/// The only warning of `r` (its fault and sweep checked).
const core::FrameWarning& onlyWarning(const FaultedRun& r, core::FrameFault fault, long sweep) {
  static const core::FrameWarning none{};
  EXPECT_EQ(r.warnings.size(), 1u);
  for (const auto& w : r.warnings) std::printf("  warning: %s\n", w.text().c_str());
  if (r.warnings.empty()) return none;
  EXPECT_EQ(r.warnings[0].fault, fault) << r.warnings[0].text();
  EXPECT_EQ(r.warnings[0].sweep, sweep) << r.warnings[0].text();
  return r.warnings[0];
}

/// Removes every return of the columns [first, last) of `f` (and their input points).
void emptyColumns(core::LidarFrame& f, int first, int last) {
  for (int r = 0; r < f.rows(); r++)
    for (int c = first; c < last; c++) f.clearPixel(r, c);
  for (std::int32_t& px : f.point_pixel)
    if (px >= 0 && px % f.cols() >= first && px % f.cols() < last) px = -1;
}

/// Shuffles the columns of `f` (each column's pixels and input points move together).
void shuffleColumns(core::LidarFrame& f, std::mt19937& rng) {
  std::vector<int> to(static_cast<std::size_t>(f.cols()));  // old column -> new column
  std::iota(to.begin(), to.end(), 0);
  std::shuffle(to.begin(), to.end(), rng);
  const cv::Mat_<float> range = f.range.clone(), intensity = f.intensity.clone();
  const cv::Mat_<cv::Vec3f> xyz = f.xyz.clone();
  const cv::Mat_<std::uint8_t> valid = f.valid.clone();
  const cv::Mat_<std::int32_t> source = f.source_index.clone();
  for (int c = 0; c < f.cols(); c++)
    for (int r = 0; r < f.rows(); r++) {
      const int n = to[static_cast<std::size_t>(c)];
      f.range(r, n) = range(r, c);
      f.intensity(r, n) = intensity(r, c);
      f.xyz(r, n) = xyz(r, c);
      f.valid(r, n) = valid(r, c);
      f.source_index(r, n) = source(r, c);
    }
  for (std::int32_t& px : f.point_pixel)
    if (px >= 0) px = f.pixelIndex(px / f.cols(), to[static_cast<std::size_t>(px % f.cols())]);
}

}  // namespace

TEST(FrameFaults, CleanRunHasNoWarningAndFindsTheMovers) {
  const Clean& c = clean();
  std::vector<Feed> feed;
  for (int j = 0; j < kSweeps; j++) feed.push_back(cleanFeed(j));
  EXPECT_TRUE(run(c, feed).warnings.empty());
  // The span the recoveries are measured on has movers to find (else F1 = 1 proves nothing).
  const double mean = std::accumulate(c.f1.begin() + kFault, c.f1.end(), 0.0) / (kSweeps - kFault);
  std::printf("clean: mean F1 %.3f over sweeps %d-%d\n", mean, kFault, kSweeps - 1);
  EXPECT_GT(mean, 0.5);
  EXPECT_LT(mean, 0.999);
}

TEST(FrameFaults, TimeReversalIsSkippedAndChangesNothingAfter) {
  const FaultedRun r =
      run(clean(), faulted([](int j, std::vector<Feed>& f) {
            if (j == kFault)
              f.push_back({clean().sweeps[kFault - 5].frame, -1});  // an old sweep again
            f.push_back(cleanFeed(j));
          }));
  const auto& w = onlyWarning(r, core::FrameFault::TimeReversal, kFault);
  EXPECT_NEAR(w.figure, 0.4, 1e-6);  // 0.4 s before sweep 29
  EXPECT_EQ(recovery(r, kFault, "time reversal"), 0);
}

TEST(FrameFaults, DuplicateTimestampIsSkipped) {
  const FaultedRun r = run(clean(), faulted([](int j, std::vector<Feed>& f) {
                             f.push_back(cleanFeed(j));
                             if (j == kFault - 1)
                               f.push_back({clean().sweeps[kFault - 1].frame, -1});
                           }));
  onlyWarning(r, core::FrameFault::DuplicateTime, kFault);
  EXPECT_EQ(recovery(r, kFault, "duplicate timestamp"), 0);
}

TEST(FrameFaults, DuplicateContentIsSkippedAndKeepsTheSweepBeforesPixels) {
  core::LidarFrame again = deepCopy(clean().sweeps[kFault - 1].frame);
  again.timestamp_ns += kPeriodNs / 2;
  const FaultedRun r =
      run(clean(), faulted([&](int j, std::vector<Feed>& f) {
            f.push_back(cleanFeed(j));
            if (j == kFault - 1)
              f.push_back({again, kFault - 1});  // scored: the same points, same answer
          }));
  onlyWarning(r, core::FrameFault::DuplicateContent, kFault);
  EXPECT_EQ(recovery(r, kFault, "duplicate sweep"), 0);
}

TEST(FrameFaults, MissingSweepsWarn) {
  const FaultedRun r = run(clean(), faulted([](int j, std::vector<Feed>& f) {
                             if (j < kFault || j >= kFault + 3) f.push_back(cleanFeed(j));
                           }));
  const auto& w = onlyWarning(r, core::FrameFault::MissingSweeps, kFault);
  EXPECT_NEAR(w.figure, 0.4, 1e-6);
  EXPECT_LE(recovery(r, kFault + 3, "3 missing sweeps"), 2);
}

TEST(FrameFaults, TimeJumpRestartsTheTracks) {
  const FaultedRun r = run(clean(), faulted([](int j, std::vector<Feed>& f) {
                             Feed s = cleanFeed(j);
                             if (j >= kFault)
                               s.frame.timestamp_ns += 2000000000LL;  // the clock jumps 2 s ahead
                             f.push_back(s);
                           }));
  const auto& w = onlyWarning(r, core::FrameFault::TimeJump, kFault);
  EXPECT_NEAR(w.figure, 2.1, 1e-6);
  EXPECT_LE(recovery(r, kFault, "time jump"), 16);  // the warm-up of a fresh detector
}

TEST(FrameFaults, ClockStepBackRestartsLikeAFreshDetector) {
  // The recording played again from its start after its first kFault sweeps (time goes back 2.9
  // s): a time jump, and from there the results of a fresh detector (the clean run's).
  std::vector<Feed> feed;
  for (int j = 0; j < kFault; j++) feed.push_back(cleanFeed(j));
  for (int j = 0; j < kSweeps; j++) feed.push_back(cleanFeed(j));
  const FaultedRun r = run(clean(), feed);
  const auto& w = onlyWarning(r, core::FrameFault::TimeJump, kFault);
  EXPECT_NEAR(w.figure, -2.9, 1e-6);
  EXPECT_EQ(recovery(r, 0, "clock step back"), 0);
}

TEST(FrameFaults, PartialSweepWarns) {
  const FaultedRun r = run(clean(), faulted([](int j, std::vector<Feed>& f) {
                             Feed s = cleanFeed(j);
                             if (j == kFault)
                               emptyColumns(s.frame, 307, 512);  // the last 40 % of the revolution
                             f.push_back(s);
                           }));
  const auto& w = onlyWarning(r, core::FrameFault::LostColumns, kFault);
  EXPECT_NEAR(w.figure, 0.4, 0.01);
  EXPECT_LE(recovery(r, kFault + 1, "partial sweep"), 2);
}

TEST(FrameFaults, BlockedHalfWarns) {
  const FaultedRun r = run(clean(), faulted([](int j, std::vector<Feed>& f) {
                             Feed s = cleanFeed(j);
                             if (j >= kFault && j < kFault + 10)
                               emptyColumns(s.frame, 0, 256);  // half blocked for 1 s
                             f.push_back(s);
                           }));
  const auto& w = onlyWarning(r, core::FrameFault::LostColumns, kFault);
  EXPECT_NEAR(w.figure, 0.5, 0.01);
  EXPECT_NE(w.message.find("widest gap 180 deg"), std::string::npos) << w.message;
  EXPECT_LE(recovery(r, kFault + 10, "blocked half"), 2);
}

TEST(FrameFaults, SweepOverMoreThan360DegreesWarns) {
  const FaultedRun r =
      run(clean(), faulted([](int j, std::vector<Feed>& f) {
            Feed s = cleanFeed(j);
            if (j == kFault) {  // the next revolution's first 40 degrees (57 columns) in it too
              const core::LidarFrame& next = clean().sweeps[kFault + 1].frame;
              for (int row = 0; row < next.rows(); row++)
                for (int col = 0; col < 57; col++) {
                  if (!next.isValid(row, col)) continue;
                  const auto src = static_cast<std::int32_t>(s.frame.point_pixel.size());
                  s.frame.point_pixel.push_back(s.frame.pixelIndex(row, col));
                  if (!s.frame.isValid(row, col) || next.range(row, col) < s.frame.range(row, col))
                    s.frame.setPixel(row, col, next.range(row, col), next.intensity(row, col),
                                     next.xyz(row, col), src);
                }
            }
            f.push_back(s);
          }));
  const auto& w = onlyWarning(r, core::FrameFault::WideSweep, kFault);
  EXPECT_NEAR(w.figure, 40.0, 6.0);
  EXPECT_LE(recovery(r, kFault + 1, "sweep over 400 degrees"), 2);
}

TEST(FrameFaults, ZeroIntensityWarns) {
  const FaultedRun r = run(clean(), faulted([](int j, std::vector<Feed>& f) {
                             Feed s = cleanFeed(j);
                             if (j >= kFault && j < kFault + 3) s.frame.intensity.setTo(0);
                             f.push_back(s);
                           }));
  onlyWarning(r, core::FrameFault::ZeroIntensity, kFault);
  EXPECT_LE(recovery(r, kFault + 3, "zero intensity"), 2);
}

TEST(FrameFaults, LongRunOfEgoMotionFailuresWarns) {
  // 12 sweeps with their columns shuffled (seeded): no motion explains them.
  std::mt19937 rng(7);
  const FaultedRun r = run(clean(), faulted([&](int j, std::vector<Feed>& f) {
                             Feed s = cleanFeed(j);
                             if (j >= kFault && j < kFault + 12) shuffleColumns(s.frame, rng);
                             f.push_back(s);
                           }));
  // The sweep where the ego-motion had failed 10 times in a row ([frame_check] max_ego_failures).
  long tenth = -1;
  for (std::size_t k = 0, run_length = 0; k < r.ego_ok.size() && tenth < 0; k++)
    if ((run_length = r.ego_ok[k] ? 0 : run_length + 1) == 10) tenth = static_cast<long>(k);
  ASSERT_GE(tenth, kFault + 9);  // no earlier run; this one failed on 10 of its 12 sweeps at least
  const auto& w = onlyWarning(r, core::FrameFault::EgoMotionFailures, tenth);
  EXPECT_DOUBLE_EQ(w.figure, 10.0);
  EXPECT_LE(recovery(r, kFault + 12, "12 ego-motion failures"), 12);
}
