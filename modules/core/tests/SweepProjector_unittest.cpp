// SPDX-License-Identifier: BSD-3-Clause
// SweepProjector: a recording's unordered sweeps into frames: one intensity scale for the whole
// recording (decided on its first sweep), the rows of the first complete sweep kept for the later
// ones, reset() starting a new recording. Sweeps of UnorderedSweep.h (true beam of each point).
#include <dynobj/core/SweepProjector.h>
#include <gtest/gtest.h>

#include <stdexcept>

#include "UnorderedSweep.h"

using dynobj::core::LidarFrame;
using dynobj::core::PointCloud;
using dynobj::core::RowSource;
using dynobj::core::SweepProjector;
using dynobj::test::firingOrderSweep;
using dynobj::test::hint;
using dynobj::test::shuffle;

namespace {

/// Checks that each point of `c` sits in the row of its true beam.
void expectRows(const LidarFrame& f, const std::vector<int>& laser) {
  ASSERT_EQ(f.point_pixel.size(), laser.size());
  for (std::size_t i = 0; i < laser.size(); i++) {
    ASSERT_GE(f.point_pixel[i], 0) << "point " << i;
    ASSERT_EQ(f.point_pixel[i] / f.cols(), laser[i]) << "point " << i;
  }
}

}  // namespace

TEST(SweepProjector, FractionalIntensityIsScaledOnceForTheWholeRecording) {
  std::vector<int> laser;
  PointCloud first = firingOrderSweep(laser);
  for (float& v : first.intensity) v /= 10;     // 0 - 0.5: a KITTI remission
  PointCloud second = firingOrderSweep(laser);  // 0 - 5: would be integer-valued on its own
  const PointCloud given = second;

  SweepProjector p;
  EXPECT_EQ(p.intensityScale(), 0.0);
  LidarFrame f;
  p.project(first, f);
  EXPECT_EQ(p.intensityScale(), 255.0);
  p.project(second, f);
  EXPECT_EQ(p.intensityScale(), 255.0);
  for (std::size_t i = 0; i < second.size(); i++)
    ASSERT_FLOAT_EQ(second.intensity[i], given.intensity[i] * 255.0f) << "point " << i;

  SweepProjector fresh;  // the second sweep as a recording of its own: kept as it is
  PointCloud alone = given;
  fresh.project(alone, f);
  EXPECT_EQ(fresh.intensityScale(), 1.0);
  EXPECT_EQ(alone.intensity, given.intensity);
}

TEST(SweepProjector, TheFirstCompleteSweepGivesTheRowsOfTheLaterOnes) {
  std::vector<int> laser;
  PointCloud first = firingOrderSweep(laser);
  SweepProjector p;
  LidarFrame f;
  p.project(first, f);
  EXPECT_EQ(p.lastRowSource(), RowSource::FiringOrder);
  EXPECT_EQ(p.lastLasers(), 6);
  expectRows(f, laser);

  // A shuffled sweep has no row rule of its own: it takes the rows learned from the first one.
  std::vector<int> shuffled_laser;
  PointCloud shuffled = firingOrderSweep(shuffled_laser, 20 * dynobj::test::kDeg);
  shuffle(shuffled, shuffled_laser);
  const PointCloud shuffled_copy = shuffled;
  p.project(shuffled, f);
  EXPECT_NE(p.lastRowSource(), RowSource::FiringOrder);
  EXPECT_EQ(f.rows(), 6);
  expectRows(f, shuffled_laser);

  // A new recording (reset, or a new projector) without a sensor model: no rows for it.
  p.reset();
  EXPECT_EQ(p.intensityScale(), 0.0);
  PointCloud again = shuffled_copy;
  EXPECT_THROW(p.project(again, f), std::invalid_argument);
  PointCloud once_more = shuffled_copy;
  EXPECT_THROW(SweepProjector().project(once_more, f), std::invalid_argument);

  // With a sensor model the shuffled sweep is placed by its elevation histogram.
  SweepProjector with_sensor(hint());
  PointCloud with = shuffled_copy;
  with_sensor.project(with, f);
  EXPECT_EQ(with_sensor.lastRowSource(), RowSource::EstimatedTable);
  expectRows(f, shuffled_laser);
}
