// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/LabelFile.h>
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/sim/LidarSimulator.h>
#include <dynobj/sim/SequenceWriter.h>
#include <dynobj/sim/TopView.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/system/filesystem.h>

#include <cmath>
#include <fstream>

#include "SimTestUtil.h"

using namespace dynobj;
using namespace dynobj::sim;
using namespace dynobj::sim::test;

TEST(LidarSimulator, FloorAtKnownDistance) {
  const LidarSimulator sim(load(base("")));
  const auto sw = sim.simulate(0);
  const auto elev = sim.scenario().sensor.rowElevations();
  for (int r = 0; r < 8; r++) {
    SCOPED_TRACE(r);
    if (elev[static_cast<std::size_t>(r)] >= 0) {
      EXPECT_EQ(cv::countNonZero(sw.frame.valid.row(r)), 0);  // nothing above the horizon
      continue;
    }
    const double expected = 1.0 / std::sin(-elev[static_cast<std::size_t>(r)]);  // h / sin(-el)
    for (int c = 0; c < 64; c++) {
      ASSERT_TRUE(sw.frame.isValid(r, c));
      EXPECT_NEAR(sw.frame.range(r, c), expected, 1e-4);
      EXPECT_NEAR(sw.frame.xyz(r, c)[2], -1.0, 1e-4);
    }
  }
}

TEST(LidarSimulator, CylinderAtKnownDistanceAndLabels) {
  // A moving pedestrian straight ahead at 6 m, a standing one on the left, and one hidden
  // behind a wall on the right.
  const LidarSimulator sim(load(
      base("static:\n  - {box: {center: [0, -5, 2], size: [20, 0.2, 4]}}\n"
           "  - {cylinder: {center: [-8, 0], radius: 0.5, height: 3}}\n"
           "actors:\n"
           "  - {class: pedestrian, height: 1.75, trajectory: {type: waypoints, points: [[6, -1], "
           "[6, 1]], speed: 0.5}}\n"
           "  - {class: pedestrian, height: 1.75, trajectory: {type: stationary, at: [0, 4]}}\n"
           "  - {class: pedestrian, height: 1.75, trajectory: {type: waypoints, points: [[-3, -8], "
           "[3, -8]], speed: 1}}\n")));
  const auto sw = sim.simulate(2);
  // Static cylinder (r = 0.5) 8 m behind the sensor. Column 0's ray is pi/64 off the direction
  // to its axis: horizontal distance 8 cos(d) - sqrt(0.25 - 64 sin^2(d)), at elevation 2 deg.
  const double d = M_PI / 64;
  const double t_h = 8 * std::cos(d) - std::sqrt(0.25 - 64 * std::sin(d) * std::sin(d));
  EXPECT_NEAR(sw.frame.range(3, 0), t_h / std::cos(2 * kDeg), 1e-4);
  ASSERT_EQ(sw.actors.size(), 3u);
  EXPECT_TRUE(sw.actors[0].moving);
  EXPECT_FALSE(sw.actors[1].moving);
  EXPECT_TRUE(sw.actors[2].moving);
  EXPECT_GT(sw.actors[0].points, 3);
  EXPECT_GT(sw.actors[1].points, 3);
  EXPECT_EQ(sw.actors[2].points, 0);  // occluded by the wall: no pixels, no labels
  for (int r = 0; r < 8; r++)
    for (int c = 0; c < 64; c++) {
      const bool dyn = sw.dynamic(r, c) != 0;
      EXPECT_EQ(dyn, sw.actor(r, c) == 0) << r << "," << c;  // exactly the moving actor's pixels
    }
}

TEST(LidarSimulator, DeterministicPerSweep) {
  const LidarSimulator sim(
      Scenario::fromYamlFile(std::string(DYNOBJ_SHARE_DIR) + "/scenarios/hall.yaml",
                             DYNOBJ_SHARE_DIR, {{"frames", "10"}}));
  const auto a = sim.simulate(5);
  sim.simulate(3);
  const auto b = sim.simulate(5);
  EXPECT_EQ(cv::norm(a.frame.range, b.frame.range, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(a.frame.intensity, b.frame.intensity, cv::NORM_INF), 0.0);
  EXPECT_GT(a.frame.validCount(), 20000u);
  EXPECT_GT(cv::countNonZero(a.dynamic), 0);
}

TEST(LidarSimulator, SequenceFilesRoundTrip) {
  const LidarSimulator sim(load(
      base("actors:\n  - {class: pedestrian, trajectory: {type: waypoints, points: [[5, -2], [5, "
           "2]], speed: 1}}\n",
           "{trajectory: {type: waypoints, points: [[0, 0], [3, 0]], speed: 1, loop: false}}")));
  const std::string dir = dynobj::testing::scratchPath("_seq");
  std::vector<SimulatedSweep> sweeps;
  {
    SequenceWriter w(dir, sim.scenario());
    for (int k = 0; k < 10; k++) {
      sweeps.push_back(sim.simulate(k));
      w.write(sweeps.back());
    }
    w.close();
  }
  // Labels: one line per sweep with exactly the dynamic pixels.
  const auto labels = io::LabelFile::read(dir + "/t.gt.labels");
  ASSERT_EQ(labels.sweeps.size(), 10u);
  for (int k = 0; k < 10; k++) {
    EXPECT_EQ(labels.sweeps[k].timestamp_ns, sweeps[k].timestamp_ns);
    EXPECT_EQ(labels.sweeps[k].pixels, io::pixelsOfMask(sweeps[k].dynamic));
  }
  // TUM: the scenario's sensor trajectory (platform moves 1 m/s along +X, sensor 1 m up).
  std::ifstream tum(dir + "/t.gt.tum");
  std::string line;
  std::getline(tum, line);  // header
  for (int k = 0; k < 10; k++) {
    double ts, x, y, z, qx, qy, qz, qw;
    tum >> ts >> x >> y >> z >> qx >> qy >> qz >> qw;
    EXPECT_NEAR(ts, 1.7e9 + 0.1 * k, 1e-6);
    EXPECT_NEAR(x, 0.1 * k, 1e-6);
    EXPECT_NEAR(z, 1.0, 1e-6);
    EXPECT_NEAR(qw, 1.0, 1e-6);
  }
  // Rawlog: the scans convert back to the simulated frames.
  dynobj::mrptio::RawlogReader reader(dir + "/t.rawlog");
  dynobj::mrptio::RawlogEntry e;
  int scans = 0;
  while (reader.next(e)) {
    auto scan = std::dynamic_pointer_cast<::mrpt::obs::CObservation3DRangeScan>(e.observation);
    ASSERT_TRUE(scan);
    core::LidarFrame f;
    dynobj::mrptio::ObservationConverter().convert(*scan, f);
    EXPECT_EQ(f.validCount(), sweeps[static_cast<std::size_t>(scans)].frame.validCount());
    EXPECT_EQ(f.timestamp_ns, sweeps[static_cast<std::size_t>(scans)].timestamp_ns);
    scans++;
  }
  EXPECT_EQ(scans, 10);
  // objects CSV: header + one row per sweep and actor.
  std::ifstream csv(dir + "/t.gt.objects.csv");
  int lines = 0;
  while (std::getline(csv, line)) lines++;
  EXPECT_EQ(lines, 1 + 10);
}

TEST(LidarSimulator, MotionDistortionShiftsColumnsOnlyWhenMoving) {
  // The robot drives at 5 m/s along +X towards a wall across its path: with distortion, columns
  // fired later see the wall from nearer, so ranges differ from the undistorted sweep; standing
  // still, nothing changes.
  const std::string wall = "static:\n  - {box: {center: [8, 0, 1.5], size: [0.2, 40, 3]}}\n";
  const std::string drive =
      "{trajectory: {type: waypoints, points: [[-10, 0], [10, 0]], speed: 5, loop: false}}";
  auto run = [&](const std::string& platform, bool distortion) {
    auto s = load(base(wall, platform));
    s.motion_distortion = distortion;
    return LidarSimulator(s).simulate(5);
  };
  const auto moving_plain = run(drive, false), moving_dist = run(drive, true);
  const auto still_plain = run("{trajectory: {type: stationary, at: [0, 0]}}", false);
  const auto still_dist = run("{trajectory: {type: stationary, at: [0, 0]}}", true);
  EXPECT_EQ(cv::norm(still_plain.frame.range, still_dist.frame.range, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(moving_plain.frame.range, moving_dist.frame.range, cv::NORM_INF), 0.05);
}

TEST(LidarSimulator, TopViewShowsMovingActorsInRed) {
  const LidarSimulator sim(load(base(
      "actors:\n  - {class: pedestrian, trajectory: {type: waypoints, points: [[5, -2], [5, "
      "2]], speed: 1}}\n  - {class: pedestrian, trajectory: {type: stationary, at: [0, 3]}}\n")));
  const auto sw = sim.simulate(3);
  const cv::Mat img = topView(sw, {sw.sensor_pose.translation()}, 0.1, 10.0);
  ASSERT_EQ(img.rows, 200);
  // Sensor at the centre (100, 100), 0.1 m per pixel, +y up: the walker red, the stander blue.
  ASSERT_GT(sw.actors[0].points, 0);
  ASSERT_GT(sw.actors[1].points, 0);
  auto colourAt = [&](const Eigen::Vector3d& p) {
    const int x = static_cast<int>(100 + p.x() * 10), y = static_cast<int>(100 - p.y() * 10);
    cv::Vec3b best(0, 0, 0);
    for (int dy = -5; dy <= 5; dy++)
      for (int dx = -5; dx <= 5; dx++) {
        const cv::Vec3b v = img.at<cv::Vec3b>(y + dy, x + dx);
        if (v[2] > 200 && v[0] < 100) return std::string("red");
        if (v[0] > 200 && v[2] < 100) best = v;
      }
    return std::string(best[0] > 200 ? "blue" : "none");
  };
  EXPECT_EQ(colourAt(sw.actors[0].position), "red");
  EXPECT_EQ(colourAt(sw.actors[1].position), "blue");
}
