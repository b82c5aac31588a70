// SPDX-License-Identifier: BSD-3-Clause
// Real sensor traits: Velodyne 0-255 intensities, a unit's own beam errors, and the unordered
// point-cloud output (laser by laser in firing order, remission 0-1) that the project's reader
// turns back into the same image.
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/sim/LidarSimulator.h>
#include <dynobj/sim/SequenceWriter.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include <cmath>

#include "SimTestUtil.h"

using namespace dynobj;
using namespace dynobj::sim;
using namespace dynobj::sim::test;

namespace {

/// A closed room around the sensor (every beam returns in every column).
const std::string kRoom =
    "static:\n"
    "  - {box: {center: [8, 0, 3], size: [0.4, 16.4, 6]}, material: {albedo: 1.0, pattern: "
    "plain}}\n"
    "  - {box: {center: [-8, 0, 3], size: [0.4, 16.4, 6]}, material: {albedo: 0.5, pattern: "
    "noise}}\n"
    "  - {box: {center: [0, 8, 3], size: [16.4, 0.4, 6]}, material: {albedo: 0.5, pattern: "
    "posters}}\n"
    "  - {box: {center: [0, -8, 3], size: [16.4, 0.4, 6]}, material: {albedo: 0.5, pattern: "
    "checker}}\n";

}  // namespace

TEST(SensorTraits, VelodyneIntensityIsCalibratedReflectivity) {
  // A white plain wall at 8 m: 100 x (0.4 + 0.6 cos incidence) +- the unit noise of 1 count.
  const LidarSimulator sim(load(base(kRoom + "intensity: {model: velodyne, noise: 0}\n")));
  const auto sw = sim.simulate(0);
  const auto elev = sim.scenario().sensor.rowElevations();
  for (int c = 26; c < 38; c++) {  // columns facing +X
    const double az = -M_PI + (c + 0.5) * 2 * M_PI / 64;
    if (std::abs(az) > 0.5) continue;
    for (int r = 2; r < 6; r++) {
      ASSERT_TRUE(sw.frame.isValid(r, c));
      const double cosi = std::cos(elev[static_cast<std::size_t>(r)]) * std::cos(az);
      EXPECT_NEAR(sw.frame.intensity(r, c), 100 * (0.4 + 0.6 * cosi), 6.0) << r << "," << c;
    }
  }
  double lo = 1e9, hi = -1e9;
  for (int r = 0; r < 8; r++)
    for (int c = 0; c < 64; c++)
      if (sw.frame.isValid(r, c)) {
        const float v = sw.frame.intensity(r, c);
        EXPECT_EQ(v, std::round(v));
        lo = std::min<double>(lo, v);
        hi = std::max<double>(hi, v);
      }
  EXPECT_GE(lo, 0.0);
  EXPECT_LE(hi, 255.0);
}

TEST(SensorTraits, UnitBeamErrorsFromTheSeed) {
  const std::string unit = "sensor_unit: {elevation_sigma_deg: 0.3, azimuth_sigma_deg: 0.2}\n";
  const Scenario s = load(base(unit));
  ASSERT_EQ(s.beam_elevation_error.size(), 8u);
  double sum2 = 0;
  for (double e : s.beam_elevation_error) sum2 += e * e;
  EXPECT_GT(sum2, 0.0);
  EXPECT_LT(std::sqrt(sum2 / 8), 1.0 * kDeg);
  // The floor is seen at the unit's own elevations: range = h / sin(-(nominal + error)).
  const LidarSimulator sim(s);
  const auto sw = sim.simulate(0);
  const auto elev = s.sensor.rowElevations();
  for (int r = 5; r < 8; r++) {
    const double el =
        elev[static_cast<std::size_t>(r)] + s.beam_elevation_error[static_cast<std::size_t>(r)];
    EXPECT_NEAR(sw.frame.range(r, 10), 1.0 / std::sin(-el), 1e-4);
    const cv::Vec3f p = sw.frame.xyz(r, 10);
    const double az =
        -M_PI + 10.5 * 2 * M_PI / 64 + s.beam_azimuth_error[static_cast<std::size_t>(r)];
    EXPECT_NEAR(std::atan2(p[1], p[0]), az, 1e-5);
  }
  // Another seed is another unit; `seed:` pins one unit across scenario seeds.
  const auto other = Scenario::fromYamlText(base(unit), DYNOBJ_SHARE_DIR, {{"seed", "2"}}, "t");
  EXPECT_NE(other.beam_elevation_error, s.beam_elevation_error);
  const std::string pinned = "sensor_unit: {elevation_sigma_deg: 0.3, seed: 77}\n";
  EXPECT_EQ(Scenario::fromYamlText(base(pinned), DYNOBJ_SHARE_DIR, {{"seed", "2"}}, "t")
                .beam_elevation_error,
            Scenario::fromYamlText(base(pinned), DYNOBJ_SHARE_DIR, {{"seed", "3"}}, "t")
                .beam_elevation_error);
  EXPECT_TRUE(load(base("")).beam_elevation_error.empty());  // a perfect unit by default
}

TEST(SensorTraits, PointCloudOutputInFiringOrderReadsBackAsTheSameImage) {
  const LidarSimulator sim(load(base(kRoom + "output: point_cloud\n")));
  const std::string dir = dynobj::testing::scratchPath("_pc");
  std::vector<SimulatedSweep> sweeps;
  {
    SequenceWriter w(dir, sim.scenario());
    for (int k = 0; k < 3; k++) {
      sweeps.push_back(sim.simulate(k));
      w.write(sweeps.back());
    }
    w.close();
  }
  dynobj::mrptio::RawlogReader reader(dir + "/t.rawlog");
  dynobj::mrptio::RawlogEntry e;
  int n = 0;
  const dynobj::mrptio::ObservationConverter converter;  // no sensor model: rows from the data
  while (reader.next(e)) {
    auto obs = std::dynamic_pointer_cast<::mrpt::obs::CObservationPointCloud>(e.observation);
    ASSERT_TRUE(obs);
    const SimulatedSweep& sw = sweeps[static_cast<std::size_t>(n++)];
    const auto* pc = dynamic_cast<const ::mrpt::maps::CPointsMapXYZI*>(obs->pointcloud.get());
    ASSERT_NE(pc, nullptr);
    ASSERT_EQ(pc->size(), sw.frame.validCount());
    // Laser 0 (the top beam here) first, its columns from W-1 down to 0: azimuth decreasing.
    const auto& xs = pc->getPointsBufferRef_x();
    const auto& ys = pc->getPointsBufferRef_y();
    EXPECT_GT(std::atan2(ys[0], xs[0]), std::atan2(ys[1], xs[1]));
    for (float v : pc->getPointsBufferRef_intensity()) {
      EXPECT_GE(v, 0.0f);
      EXPECT_LE(v, 1.0f);
    }
    core::LidarFrame f;
    converter.convert(*obs, f);
    ASSERT_EQ(f.rows(), 8);
    ASSERT_EQ(f.cols(), 64);
    EXPECT_EQ(cv::norm(f.valid, sw.frame.valid, cv::NORM_L1), 0.0);
    EXPECT_LT(cv::norm(f.range, sw.frame.range, cv::NORM_INF), 1e-5);
  }
  EXPECT_EQ(n, 3);
}
