// SPDX-License-Identifier: BSD-3-Clause
// Row recovery for unordered clouds: each rule on a hand-made sweep whose true beam of every
// point is known (an uneven 6-beam table, like a real unit's).
#include <dynobj/core/RowRecovery.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

using dynobj::core::LidarFrame;
using dynobj::core::PointCloud;
using dynobj::core::projectUnordered;
using dynobj::core::recoverRows;
using dynobj::core::RowSource;
using dynobj::core::SensorModel;

namespace {

constexpr double kDeg = M_PI / 180.0;
/// Beam elevations [deg] top-down, unevenly spaced.
const std::vector<double> kBeams = {4.1, 2.0, 1.2, -3.5, -4.0, -9.0};
constexpr int kFirings = 360;

/// One sweep stored laser by laser (top beam first), each laser one revolution starting at
/// azimuth `start`; every 7th firing of each laser is a no-return. `laser` receives each point's
/// beam (index into kBeams). Ranges 20-40 m.
PointCloud firingOrderSweep(std::vector<int>& laser, double start = 10 * kDeg,
                            int lasers = static_cast<int>(kBeams.size())) {
  PointCloud c;
  laser.clear();
  for (int l = 0; l < lasers; l++)
    for (int k = 0; k < kFirings; k++) {
      if ((k + l) % 7 == 0) continue;
      const double az = start + 2 * M_PI * k / kFirings, el = kBeams[l] * kDeg;
      const double r = 20.0 + 20.0 * ((k * 37 + l * 11) % 100) / 100.0;
      c.push_back(static_cast<float>(r * std::cos(el) * std::cos(az)),
                  static_cast<float>(r * std::cos(el) * std::sin(az)),
                  static_cast<float>(r * std::sin(el)), static_cast<float>(l));
      laser.push_back(l);
    }
  return c;
}

SensorModel hint(int cols = kFirings) {
  SensorModel s;
  s.model = "six";
  s.rows = static_cast<int>(kBeams.size());
  s.cols = cols;
  s.elevation_top = 5 * kDeg;  // a nominal, evenly spaced table: wrong for this unit
  s.elevation_bottom = -10 * kDeg;
  return s;
}

/// Shuffles the points of `c` (and `laser` with them), with a fixed seed.
void shuffle(PointCloud& c, std::vector<int>& laser) {
  std::vector<std::size_t> order(c.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  PointCloud out;
  std::vector<int> l;
  for (std::size_t i : order) {
    out.push_back(c.x[i], c.y[i], c.z[i], c.intensity[i]);
    if (!c.ring.empty()) out.ring.push_back(c.ring[i]);
    l.push_back(laser[i]);
  }
  c = out;
  laser = l;
}

}  // namespace

TEST(RowRecovery, FiringOrderGivesOneBeamPerRowWithTheMeasuredTable) {
  std::vector<int> laser;
  PointCloud c = firingOrderSweep(laser);
  const auto rec = recoverRows(c, std::nullopt);
  EXPECT_EQ(rec.source, RowSource::FiringOrder);
  ASSERT_EQ(rec.sensor.rows, 6);
  EXPECT_EQ(rec.sensor.cols, kFirings);  // one column per firing, from the azimuth step
  ASSERT_TRUE(c.isOrganized());
  for (std::size_t i = 0; i < c.size(); i++) ASSERT_EQ(c.row[i], laser[i]) << "point " << i;
  const auto table = rec.sensor.rowElevations();
  for (std::size_t r = 0; r < kBeams.size(); r++) EXPECT_NEAR(table[r] / kDeg, kBeams[r], 1e-3);
}

TEST(RowRecovery, FiringOrderFromBottomToTopIsFlipped) {
  std::vector<int> laser;
  PointCloud up = firingOrderSweep(laser);
  // Reverse the laser blocks (bottom laser stored first), keeping each laser's azimuth order.
  PointCloud c;
  std::vector<int> l2;
  for (int l = static_cast<int>(kBeams.size()) - 1; l >= 0; l--)
    for (std::size_t i = 0; i < up.size(); i++)
      if (laser[i] == l) {
        c.push_back(up.x[i], up.y[i], up.z[i], up.intensity[i]);
        l2.push_back(l);
      }
  const auto rec = recoverRows(c, hint());
  EXPECT_EQ(rec.source, RowSource::FiringOrder);
  for (std::size_t i = 0; i < c.size(); i++) ASSERT_EQ(c.row[i], l2[i]);
}

TEST(RowRecovery, RingFieldInAnyIdOrder) {
  std::vector<int> laser;
  PointCloud c = firingOrderSweep(laser);
  const std::vector<std::uint16_t> id_of_beam = {3, 0, 5, 1, 4, 2};  // interleaved ids
  for (int l : laser) c.ring.push_back(id_of_beam[static_cast<std::size_t>(l)]);
  shuffle(c, laser);
  const auto rec = recoverRows(c, std::nullopt);
  EXPECT_EQ(rec.source, RowSource::RingField);
  for (std::size_t i = 0; i < c.size(); i++) ASSERT_EQ(c.row[i], laser[i]);
}

TEST(RowRecovery, ShuffledCloudUsesTheElevationHistogram) {
  std::vector<int> laser;
  PointCloud c = firingOrderSweep(laser);
  shuffle(c, laser);
  LidarFrame f;
  RowSource src{};
  const auto st = projectUnordered(c, hint(), f, &src);
  EXPECT_EQ(src, RowSource::EstimatedTable);
  EXPECT_EQ(st.outside_fov, 0u);
  const int W = f.cols();
  for (std::size_t i = 0; i < c.size(); i++)
    ASSERT_EQ(f.point_pixel[i] / W, laser[i]) << "point " << i;
}

TEST(RowRecovery, ShuffledCloudWithoutSensorModelIsAnError) {
  std::vector<int> laser;
  PointCloud c = firingOrderSweep(laser);
  shuffle(c, laser);
  EXPECT_THROW(recoverRows(c, std::nullopt), std::invalid_argument);
}

TEST(RowRecovery, PartialSweepKeepsTheSensorsRows) {
  // The first sweep's recovered rows are the hint; a later sweep with only 4 lasers keeps them.
  std::vector<int> laser;
  PointCloud full = firingOrderSweep(laser);
  const SensorModel learned = recoverRows(full, std::nullopt).sensor;
  PointCloud part = firingOrderSweep(laser, 10 * kDeg, 4);
  const auto rec = recoverRows(part, learned);
  EXPECT_EQ(rec.sensor.rows, 6);
  for (std::size_t i = 0; i < part.size(); i++) ASSERT_EQ(part.row[i], laser[i]);
}

TEST(RowRecovery, WrongRowCountFallsBackToTheTable) {
  std::vector<int> laser;
  PointCloud c = firingOrderSweep(laser);
  SensorModel eight = hint();
  eight.rows = 8;  // a preset for another sensor: no rule but the nominal table fits
  const auto rec = recoverRows(c, eight);
  EXPECT_EQ(rec.source, RowSource::NominalTable);
  EXPECT_FALSE(c.isOrganized());
}
