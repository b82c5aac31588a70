// SPDX-License-Identifier: BSD-3-Clause
// The realism traits (`realism:`): mixed returns and interstitial points at depth edges, per-beam
// intensity gains, retro-reflective licence plates, runs of dropouts, lost packets and walkers'
// swinging limbs; all off, the simulator is unchanged.
#include <dynobj/sim/LidarSimulator.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>

#include "SimTestUtil.h"

using namespace dynobj;
using namespace dynobj::sim;
using namespace dynobj::sim::test;

namespace {

/// 8 beams from +14 to -14 deg, 1024 columns (6.1 mrad apart, as an OS1-64): fine enough for a
/// 3-mrad footprint and a walker's legs at 5 m.
std::string fineSensor() {
  const std::string path = dynobj::testing::scratchPath("_fine.ini");
  std::ofstream(path) << "[sensor]\nmodel = fine\nrows = 8\ncols = 1024\nelevation_top = 14\n"
                         "elevation_bottom = -14\nmin_range = 0.2\nmax_range = 80\n";
  return path;
}

std::string fine(const std::string& extra) {
  return base(extra, "{trajectory: {type: stationary, at: [0, 0]}}", fineSensor());
}

/// A wall 10 m ahead (x = 10), a person standing 5 m ahead.
const std::string kPersonBeforeWall =
    "static:\n"
    "  - {box: {center: [10.2, 0, 3], size: [0.4, 30, 6]}, material: {albedo: 0.5, pattern: "
    "plain}}\n"
    "actors:\n"
    "  - {class: pedestrian, height: 1.75, trajectory: {type: stationary, at: [5, 0]}}\n";

/// Is this pixel's point in the empty gap between the person and the wall (above the floor)?
bool inTheGap(const SimulatedSweep& sw, int r, int c) {
  const cv::Vec3f& p = sw.frame.xyz(r, c);
  return sw.frame.isValid(r, c) && p[0] > 5.5 && p[0] < 9.5 && p[2] > -0.8;
}

int pointsInTheGap(const SimulatedSweep& sw) {
  int n = 0;
  for (int r = 0; r < sw.frame.rows(); r++)
    for (int c = 0; c < sw.frame.cols(); c++) n += inTheGap(sw, r, c);
  return n;
}

/// Beams at -2 deg and above see the person at 5 m and the wall at 10 m behind it: a point in the
/// gap belongs to the person when nearer to it than to the wall.
void expectLabelledByTheNearer(const SimulatedSweep& sw, int r, int c) {
  const double x = sw.frame.xyz(r, c)[0];
  if (r > 4 || !inTheGap(sw, r, c) || std::abs(x - 7.5) < 0.1) return;
  EXPECT_EQ(sw.actor(r, c), x < 7.5 ? 0 : -1) << x;
}

}  // namespace

TEST(Realism, OffByDefaultAndNoneChangesNothing) {
  const std::string scene = kPersonBeforeWall;
  const auto a = LidarSimulator(load(fine(scene))).simulate(1);
  const auto b = LidarSimulator(load(fine(scene + "realism: none\n"))).simulate(1);
  EXPECT_EQ(cv::countNonZero(a.frame.range != b.frame.range), 0);
  EXPECT_EQ(cv::countNonZero(a.frame.intensity != b.frame.intensity), 0);
  EXPECT_EQ(cv::countNonZero(a.actor != b.actor), 0);
  EXPECT_EQ(pointsInTheGap(a), 0);
}

TEST(Realism, HarshTurnsEveryTraitOnAndEachKeyOverrides) {
  const Scenario h = load(fine("realism: harsh\n"));
  EXPECT_GT(h.realism.beam_divergence, 0);
  EXPECT_GT(h.realism.beam_gain_sigma, 0);
  EXPECT_EQ(h.realism.beam_gain.size(), 8u);
  EXPECT_TRUE(h.realism.retro_reflectors);
  EXPECT_GT(h.realism.interstitial, 0);
  EXPECT_GT(h.realism.dropout_runs, 0);
  EXPECT_EQ(h.realism.packet_loss, 0);  // none in the real captures
  EXPECT_TRUE(h.realism.gait);
  EXPECT_EQ(h.realism.packet_columns, 16);  // Ouster packets
  const Scenario g =
      load(fine("realism: {profile: harsh, gait: false, dropout_runs: 0}\n"
                "intensity: {model: velodyne}\n"));
  EXPECT_FALSE(g.realism.gait);
  EXPECT_EQ(g.realism.dropout_runs, 0);
  EXPECT_GT(g.realism.beam_gain_sigma, h.realism.beam_gain_sigma);  // Velodyne's lasers differ more
  EXPECT_TRUE(g.realism.retro_reflectors);
  EXPECT_EQ(g.realism.packet_columns, 48);  // 12 blocks x 32 lasers over 8 rows
  for (const auto& [yaml, key] : std::vector<std::pair<std::string, std::string>>{
           {"realism: hard\n", "realism: unknown realism profile 'hard'"},
           {"realism: {gaits: true}\n", "gaits"},
           {"realism: {packet_loss: 1.5}\n", "realism.packet_loss: must be in [0, 1)"},
           {"realism: {beam_divergence_mrad: -1}\n", "beam_divergence_mrad"}}) {
    try {
      load(fine(yaml));
      ADD_FAILURE() << yaml;
    } catch (const ScenarioError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  }
}

TEST(Realism, FootprintOnADepthEdgeGivesAMixedEchoLabelledByItsNearerSurface) {
  // One echo for both surfaces (separation 10 m): points appear in the empty gap, each labelled
  // with the surface it lies nearer to.
  const LidarSimulator mixed(
      load(fine(kPersonBeforeWall + "realism: {beam_divergence_mrad: 5, echo_separation: 10}\n")));
  int gap = 0;
  for (int k = 0; k < 5; k++) {
    const auto sw = mixed.simulate(k);
    gap += pointsInTheGap(sw);
    for (int r = 0; r < sw.frame.rows(); r++)
      for (int c = 0; c < sw.frame.cols(); c++) {
        expectLabelledByTheNearer(sw, r, c);
      }
  }
  EXPECT_GT(gap, 0);
  // Two echoes (separation 1 m < 5 m): the stronger is reported, never a point in between;
  // some points move onto the other surface.
  const auto plain = LidarSimulator(load(fine(kPersonBeforeWall))).simulate(0);
  const auto strongest =
      LidarSimulator(load(fine(kPersonBeforeWall + "realism: {beam_divergence_mrad: 5}\n")))
          .simulate(0);
  EXPECT_EQ(pointsInTheGap(strongest), 0);
  EXPECT_GT(cv::countNonZero(plain.frame.range != strongest.frame.range), 0);
}

TEST(Realism, InterstitialPointsLieBetweenTheSurfacesLabelledByTheNearer) {
  const LidarSimulator sim(load(fine(kPersonBeforeWall + "realism: {interstitial: 0.5}\n")));
  int gap = 0;
  for (int k = 0; k < 5; k++) {
    const auto sw = sim.simulate(k);
    gap += pointsInTheGap(sw);
    for (int r = 0; r < sw.frame.rows(); r++)
      for (int c = 0; c < sw.frame.cols(); c++) expectLabelledByTheNearer(sw, r, c);
  }
  EXPECT_GT(gap, 0);
}

TEST(Realism, DropoutsComeInRunsAlongARow) {
  const LidarSimulator sim(
      load(fine("static:\n"
                "  - {box: {center: [8, 0, 3], size: [0.4, 16.4, 6]}}\n"
                "  - {box: {center: [-8, 0, 3], size: [0.4, 16.4, 6]}}\n"
                "  - {box: {center: [0, 8, 3], size: [16.4, 0.4, 6]}}\n"
                "  - {box: {center: [0, -8, 3], size: [16.4, 0.4, 6]}}\n"
                "realism: {dropout_runs: 0.1, dropout_run_length: 4}\n")));
  int lost = 0, runs = 0, pixels = 0;
  for (int k = 0; k < 5; k++) {
    const auto sw = sim.simulate(k);
    for (int r = 0; r < 8; r++)
      for (int c = 0; c < 1024; c++, pixels++) {
        const bool gone = !sw.frame.isValid(r, c);
        lost += gone;
        runs += gone && (c == 0 || sw.frame.isValid(r, c - 1));
      }
  }
  EXPECT_NEAR(static_cast<double>(lost) / pixels, 0.1, 0.02);
  EXPECT_NEAR(static_cast<double>(lost) / runs, 4.0, 0.6);
}

TEST(Realism, EachBeamHasItsOwnIntensityGain) {
  // A white plain wall ahead, Velodyne intensities without noise: each row's return is the
  // diffuse value times that beam's gain (+-1 count).
  const std::string wall =
      "static:\n  - {box: {center: [8.2, 0, 3], size: [0.4, 30, 6]}, material: {albedo: 1.0, "
      "pattern: plain}}\nintensity: {model: velodyne, noise: 0}\n";
  const Scenario s = load(fine(wall + "realism: {beam_gain_sigma: 0.3}\n"));
  ASSERT_EQ(s.realism.beam_gain.size(), 8u);
  EXPECT_NE(*std::min_element(s.realism.beam_gain.begin(), s.realism.beam_gain.end()),
            *std::max_element(s.realism.beam_gain.begin(), s.realism.beam_gain.end()));
  const auto with = LidarSimulator(s).simulate(0);
  const auto without = LidarSimulator(load(fine(wall))).simulate(0);
  const int c = 512;  // azimuth ~0: facing the wall
  for (int r = 2; r < 6; r++) {
    ASSERT_TRUE(with.frame.isValid(r, c) && without.frame.isValid(r, c));
    const double expected =
        std::min(255.0, without.frame.intensity(r, c) * s.realism.beam_gain[std::size_t(r)]);
    EXPECT_NEAR(with.frame.intensity(r, c), expected, 2.0 + 0.02 * expected) << r;
  }
}

TEST(Realism, LicencePlatesAreRetroReflectors) {
  // A car parked 6.4 m ahead, its back to the sensor: its plate is hit by the -6 deg beam.
  const std::string car =
      "intensity: {model: velodyne, noise: 0}\n"
      "actors:\n  - {class: car, height: 1.5, trajectory: {type: stationary, at: [6.42, 0]}}\n";
  auto brightest = [](const SimulatedSweep& sw) {
    float m = 0;
    for (int r = 0; r < sw.frame.rows(); r++)
      for (int c = 0; c < sw.frame.cols(); c++)
        if (sw.frame.isValid(r, c) && sw.actor(r, c) == 0)
          m = std::max(m, sw.frame.intensity(r, c));
    return m;
  };
  EXPECT_LE(brightest(LidarSimulator(load(fine(car))).simulate(0)), 101.0f);
  EXPECT_GE(
      brightest(
          LidarSimulator(load(fine(car + "realism: {retro_reflectors: true}\n"))).simulate(0)),
      250.0f);  // Velodyne: retro-reflectors above 100, here saturated
}

TEST(Realism, PacketsAreLostWholeAndInBursts) {
  // Closed room: every beam returns, so a column without points is a lost one.
  const std::string room =
      "static:\n"
      "  - {box: {center: [8, 0, 3], size: [0.4, 16.4, 6]}}\n"
      "  - {box: {center: [-8, 0, 3], size: [0.4, 16.4, 6]}}\n"
      "  - {box: {center: [0, 8, 3], size: [16.4, 0.4, 6]}}\n"
      "  - {box: {center: [0, -8, 3], size: [16.4, 0.4, 6]}}\n"
      "realism: {packet_loss: 0.02, packet_burst: 4}\n";
  const LidarSimulator sim(load(fine(room)));
  int lost = 0, packets = 0, bursts = 0;
  for (int k = 0; k < 20; k++) {
    const auto sw = sim.simulate(k);
    bool prev = false;
    for (int first = 1023; first >= 0; first -= 16, packets++) {
      int empty = 0;
      for (int c = first; c > first - 16; c--) empty += !sw.frame.isValid(4, c);
      ASSERT_TRUE(empty == 0 || empty == 16) << "sweep " << k << " packet at " << first;
      lost += empty == 16;
      bursts += empty == 16 && !prev;
      prev = empty == 16;
    }
    EXPECT_EQ(cv::countNonZero(sw.frame.range != sim.simulate(k).frame.range), 0);  // determinism
  }
  // Expected: a share p L / (1 + p L) = 7.4 % lost, in bursts of 4 on average.
  EXPECT_NEAR(static_cast<double>(lost) / packets, 0.074, 0.03);
  EXPECT_GT(static_cast<double>(lost) / std::max(1, bursts), 2.0);
}

TEST(Realism, WalkersSwingTheirLegsAndStandersDoNot) {
  // A person walking across 5 m ahead at 1.4 m/s: the shins (the -10 deg beam) move against the
  // torso (+2 deg) by up to the stride's swing; a standing person's do not.
  auto spread = [](const std::string& trajectory) {
    const LidarSimulator sim(load(
        fine("realism: {gait: true}\nactors:\n  - {class: pedestrian, height: 1.75, trajectory: " +
             trajectory + "}\n")));
    double lo = 1e9, hi = -1e9;
    for (int k = 0; k < 12; k++) {
      const auto sw = sim.simulate(k);
      auto meanY = [&](int r) {
        double sum = 0;
        int n = 0;
        for (int c = 0; c < sw.frame.cols(); c++)
          if (sw.frame.isValid(r, c) && sw.actor(r, c) == 0) {
            sum += sw.frame.xyz(r, c)[1];
            n++;
          }
        return n ? sum / n : NAN;
      };
      const double d = meanY(6) - meanY(4);
      if (std::isnan(d)) continue;
      lo = std::min(lo, d);
      hi = std::max(hi, d);
    }
    return hi - lo;
  };
  EXPECT_GT(spread("{type: waypoints, points: [[5, -4], [5, 4]], speed: 1.4, loop: false}"), 0.15);
  EXPECT_LT(spread("{type: stationary, at: [5, 0]}"), 0.02);
}

TEST(Realism, AMovingVehicleRollsAndPitchesOnItsSuspension) {
  // Per-sweep changes of roll and pitch: standard deviation body_motion_deg (both axes pooled),
  // none when the platform stands still or without the trait.
  auto changeStd = [](const std::string& extra, const std::string& platform) {
    const LidarSimulator sim(load(base(extra, platform)));
    double sum2 = 0;
    int n = 0;
    for (int k = 0; k + 1 < 60; k++) {
      const double t0 = k * 0.1, t1 = t0 + 0.1;
      const Eigen::Matrix3d d = sim.robotPose(t0).linear().transpose() * sim.robotPose(t1).linear();
      const double roll = std::atan2(d(2, 1), d(2, 2)), pitch = -std::asin(d(2, 0));
      sum2 += roll * roll + pitch * pitch;
      n += 2;
    }
    return std::sqrt(sum2 / n) / kDeg;
  };
  const std::string driving =
      "{trajectory: {type: waypoints, points: [[0, 0], [100, 0]], speed: 8, loop: false}}";
  const std::string parked = "{trajectory: {type: stationary, at: [0, 0]}}";
  EXPECT_NEAR(changeStd("realism: {body_motion_deg: 0.15}\n", driving), 0.15, 0.05);
  EXPECT_LT(changeStd("", driving), 1e-9);
  EXPECT_LT(changeStd("realism: {body_motion_deg: 0.15}\n", parked), 1e-9);
}
