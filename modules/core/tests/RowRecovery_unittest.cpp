// SPDX-License-Identifier: BSD-3-Clause
// Row recovery for unordered clouds: each rule on a hand-made sweep whose true beam of every
// point is known (UnorderedSweep.h); the model of an organized cloud without a beam table.
#include <dynobj/core/RowRecovery.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <stdexcept>

#include "UnorderedSweep.h"

using dynobj::core::LidarFrame;
using dynobj::core::organizedModel;
using dynobj::core::PointCloud;
using dynobj::core::projectUnordered;
using dynobj::core::recoverRows;
using dynobj::core::RowSource;
using dynobj::core::SensorModel;

using dynobj::test::firingOrderSweep;
using dynobj::test::hint;
using dynobj::test::kBeams;
using dynobj::test::kDeg;
using dynobj::test::kFirings;
using dynobj::test::shuffle;

namespace {

/// An organized cloud (row, column per point) of beams at `elevations` [deg], top row first, 360
/// columns, ranges 20-40 m; the rows in `empty` have no point.
PointCloud organizedCloud(const std::vector<double>& elevations,
                          const std::vector<int>& empty = {}) {
  PointCloud c;
  for (int r = 0; r < static_cast<int>(elevations.size()); r++) {
    if (std::find(empty.begin(), empty.end(), r) != empty.end()) continue;
    for (int k = 0; k < 360; k++) {
      const double az = 2 * M_PI * k / 360, el = elevations[static_cast<std::size_t>(r)] * kDeg;
      const double range = 20.0 + 20.0 * ((k * 37 + r * 11) % 100) / 100.0;
      c.push_back(static_cast<float>(range * std::cos(el) * std::cos(az)),
                  static_cast<float>(range * std::cos(el) * std::sin(az)),
                  static_cast<float>(range * std::sin(el)), 1.0f, static_cast<std::uint16_t>(r),
                  static_cast<std::uint16_t>(k));
    }
  }
  return c;
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

TEST(RowRecovery, OrganizedModelMeasuresTheTableAndInterpolatesEmptyRows) {
  const PointCloud c = organizedCloud(kBeams, {2});  // row 2 (1.2 deg) without a return
  const SensorModel m = organizedModel(c, 6, 360, 80.0, "an array");
  EXPECT_EQ(m.model, "an array");
  EXPECT_EQ(m.rows, 6);
  EXPECT_EQ(m.cols, 360);
  EXPECT_DOUBLE_EQ(m.max_range, 80.0);
  EXPECT_DOUBLE_EQ(m.min_range, 0.1);
  ASSERT_EQ(m.beam_elevations.size(), 6u);
  for (std::size_t r : {0u, 1u, 3u, 4u, 5u})
    EXPECT_NEAR(m.beam_elevations[r] / kDeg, kBeams[r], 1e-4) << "row " << r;
  EXPECT_NEAR(m.beam_elevations[2] / kDeg, (2.0 - 3.5) / 2, 1e-4);  // halfway between rows 1, 3
  EXPECT_DOUBLE_EQ(organizedModel(c, 6, 360, 0.1, "short").min_range, 0.05);
}

TEST(RowRecovery, OrganizedModelFitsALineWhenTheRowsDoNotDescend) {
  // Rows 3 and 4 swapped: no strictly descending table; the least-squares line over the points
  // (an independent solver as the oracle) gives the evenly spaced model.
  const std::vector<double> swapped = {4.1, 2.0, 1.2, -4.0, -3.5, -9.0};
  const PointCloud c = organizedCloud(swapped);
  Eigen::MatrixXd a(static_cast<Eigen::Index>(c.size()), 2);
  Eigen::VectorXd el(static_cast<Eigen::Index>(c.size()));
  for (std::size_t i = 0; i < c.size(); i++) {
    const auto k = static_cast<Eigen::Index>(i);
    a(k, 0) = 1.0;
    a(k, 1) = c.row[i];
    el(k) = std::asin(c.z[i] / std::sqrt(c.x[i] * c.x[i] + c.y[i] * c.y[i] + c.z[i] * c.z[i]));
  }
  const Eigen::Vector2d fit = a.colPivHouseholderQr().solve(el);
  const SensorModel m = organizedModel(c, 6, 360, 100.0, "swapped");
  EXPECT_TRUE(m.isUniform());
  EXPECT_NEAR(m.elevation_top, fit(0), 1e-9);
  EXPECT_NEAR(m.elevation_bottom, fit(0) + 5 * fit(1), 1e-9);

  // Rows stored bottom-up: no descending line either: 1 degree per row around the horizon.
  const SensorModel up = organizedModel(organizedCloud({-9.0, -4.0, -3.5, 1.2, 2.0, 4.1}), 6, 360,
                                        100.0, "upside down");
  EXPECT_TRUE(up.isUniform());
  EXPECT_NEAR(up.elevation_top / kDeg, 2.5, 1e-12);
  EXPECT_NEAR(up.elevation_bottom / kDeg, -2.5, 1e-12);
}

namespace {

/// Each laser id's true row: its rank by elevation, top down.
std::vector<int> trueRows(const dynobj::test::FiringPattern& p) {
  std::vector<int> ids(p.elevation_deg.size());
  std::iota(ids.begin(), ids.end(), 0);
  std::stable_sort(ids.begin(), ids.end(), [&](int a, int b) {
    return p.elevation_deg[static_cast<std::size_t>(a)] >
           p.elevation_deg[static_cast<std::size_t>(b)];
  });
  std::vector<int> row(ids.size());
  for (std::size_t r = 0; r < ids.size(); r++)
    row[static_cast<std::size_t>(ids[r])] = static_cast<int>(r);
  return row;
}

}  // namespace

TEST(RowRecovery, RawFiringOrderGivesEveryRowWithoutAModel) {
  // VLP-16, HDL-32E and VLS-128-like clouds in packet order (interleaved lasers; 128 lasers fired
  // 8 at once with azimuth offsets up to 6.4 degrees, 0.11 degrees apart near the horizon; 2 %
  // no-returns, sky above the walls): every point on its true row, the table measured, one column
  // per firing; a sweep of 394 degrees keeps its repeated sector and counts it.
  for (const auto& p : {dynobj::test::vlp16Pattern(), dynobj::test::hdl32Pattern(),
                        dynobj::test::vls128Pattern()}) {
    for (double sweep : {360.0, 394.0}) {
      SCOPED_TRACE(p.name + " " + std::to_string(sweep));
      std::vector<int> laser;
      std::vector<double> turn;
      PointCloud c = dynobj::test::rawFiringSweep(p, laser, sweep, 30.0, 1, &turn);
      const auto truth = trueRows(p);
      const auto rec = recoverRows(c, std::nullopt);
      EXPECT_EQ(rec.source, RowSource::FiringCycle);
      ASSERT_EQ(rec.sensor.rows, static_cast<int>(p.elevation_deg.size()));
      EXPECT_EQ(rec.sensor.cols, p.firings);
      ASSERT_TRUE(c.isOrganized());
      std::size_t twice = 0;
      for (std::size_t i = 0; i < c.size(); i++) {
        ASSERT_EQ(c.row[i], truth[static_cast<std::size_t>(laser[i])]) << "point " << i;
        if (turn[i] >= 360.0) twice++;
      }
      EXPECT_NEAR(static_cast<double>(rec.repeated), static_cast<double>(twice), 0.01 * c.size());
      EXPECT_EQ(rec.second_pass.empty(), rec.repeated == 0);
      if (sweep == 360.0) {
        EXPECT_EQ(rec.repeated, 0u);
      }
      const auto table = rec.sensor.rowElevations();
      std::vector<double> want = p.elevation_deg;
      std::sort(want.begin(), want.end(), std::greater<>());
      // (a laser that sees only the road cannot show its few-cm vertical offset apart from its
      // elevation: VLS-128's table is off by up to a few tenths of a degree there)
      const double tolerance = p.vertical_offset_m.empty() ? 0.05 : 0.5;
      for (std::size_t r = 0; r < want.size(); r++)
        EXPECT_NEAR(table[r] / kDeg, want[r], tolerance);
    }
  }
}

TEST(RowRecovery, RawFiringOrderWithLargeVerticalOffsetsGroupsEveryLaser) {
  // HDL-64E-like: vertical offsets of 0.10-0.25 m. Every laser's points still share one row of
  // their own; but a laser that sees only the flat road shows its elevation tilted by its offset
  // (a constant, so indistinguishable from the beam's), and such lasers 0.5 degrees apart may be
  // ordered wrongly among themselves.
  const auto p = dynobj::test::hdl64Pattern();
  std::vector<int> laser;
  PointCloud c = dynobj::test::rawFiringSweep(p, laser, 394.0);
  const auto rec = recoverRows(c, std::nullopt);
  EXPECT_EQ(rec.source, RowSource::FiringCycle);
  ASSERT_EQ(rec.sensor.rows, 64);
  ASSERT_TRUE(c.isOrganized());
  std::map<std::pair<int, int>, std::size_t> pairs;  // (row, true laser) -> points
  for (std::size_t i = 0; i < c.size(); i++) pairs[{c.row[i], laser[i]}]++;
  std::map<int, std::pair<std::size_t, int>> top;  // row -> (points, laser) of its main laser
  for (const auto& [k, v] : pairs)
    if (v > top[k.first].first) top[k.first] = {v, k.second};
  std::size_t grouped = 0;
  std::set<int> lasers_of_rows;
  for (const auto& [r, t] : top) {
    grouped += t.first;
    lasers_of_rows.insert(t.second);
  }
  EXPECT_EQ(lasers_of_rows.size(), 64u);  // one laser per row
  EXPECT_GE(static_cast<double>(grouped), 0.999 * static_cast<double>(c.size()));
  const auto truth = trueRows(p);
  std::size_t right = 0;
  for (std::size_t i = 0; i < c.size(); i++)
    right += c.row[i] == truth[static_cast<std::size_t>(laser[i])];
  EXPECT_GE(static_cast<double>(right), 0.75 * static_cast<double>(c.size()));  // 0.797 here
}

TEST(RowRecovery, ShuffledRawFiringOrderIsNoFiringCycle) {
  std::vector<int> laser;
  PointCloud c = dynobj::test::rawFiringSweep(dynobj::test::vlp16Pattern(), laser);
  dynobj::test::shuffle(c, laser);
  EXPECT_THROW(recoverRows(c, std::nullopt), std::invalid_argument);
}

TEST(RowRecovery, SweepOfMoreThanOneRevolutionKeepsTheFirstPassInTheImage) {
  // 394 degrees of a VLP-16 in packet order: the first 34 degrees are scanned twice. Each pixel of
  // that sector holds its first-pass return; a second-pass point holds a pixel only where the
  // first pass had none; every point is mapped to a pixel.
  std::vector<int> laser;
  std::vector<double> turn;
  PointCloud c =
      dynobj::test::rawFiringSweep(dynobj::test::vlp16Pattern(), laser, 394.0, 30.0, 3, &turn);
  LidarFrame frame;
  RowSource source{};
  projectUnordered(c, std::nullopt, frame, &source);
  ASSERT_EQ(source, RowSource::FiringCycle);
  std::set<std::int32_t> first_pass_pixels;
  for (std::size_t i = 0; i < c.size(); i++) {
    ASSERT_GE(frame.point_pixel[i], 0);
    if (turn[i] < 360.0) first_pass_pixels.insert(frame.point_pixel[i]);
  }
  std::size_t second_held = 0;
  for (int r = 0; r < frame.sensor.rows; r++)
    for (int col = 0; col < frame.sensor.cols; col++) {
      const std::int32_t src = frame.source_index(r, col);
      if (src < 0 || turn[static_cast<std::size_t>(src)] < 360.0) continue;
      second_held++;
      EXPECT_EQ(first_pass_pixels.count(frame.pixelIndex(r, col)), 0u) << r << "," << col;
    }
  EXPECT_GT(second_held, 0u);  // holes of the first pass (2 % no-returns) filled
}
