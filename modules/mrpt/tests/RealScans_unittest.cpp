// SPDX-License-Identifier: BSD-3-Clause
// Converters on the real scans that MRPT ships in /usr/share/mrpt/datasets (package mrpt-common).
#include <dynobj/core/SensorModel.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <algorithm>
#include <cmath>

using dynobj::core::LidarFrame;
using dynobj::core::SensorModel;
using dynobj::mrptio::ObservationConverter;
using dynobj::mrptio::RawlogEntry;
using dynobj::mrptio::RawlogReader;

namespace {

const std::string kDatasets = "/usr/share/mrpt/datasets/";

mrpt::obs::CObservation::Ptr firstObservation(const std::string& file) {
  RawlogReader reader(kDatasets + file);
  RawlogEntry e;
  EXPECT_TRUE(reader.next(e));
  auto obs = e.observations();
  EXPECT_EQ(obs.size(), 1u);
  EXPECT_FALSE(reader.next(e)) << "expected a single entry";
  return obs.at(0);
}

SensorModel preset(const std::string& name) {
  return dynobj::io::readSensorModel(std::string(DYNOBJ_SHARE_DIR) + "/sensors/" + name);
}

double medianElevationDeg(const LidarFrame& f, int row) {
  std::vector<double> e;
  for (int c = 0; c < f.cols(); c++)
    if (f.isValid(row, c)) {
      const cv::Vec3f p = f.xyz(row, c);
      e.push_back(std::asin(p[2] / f.range(row, c)) * 180.0 / M_PI);
    }
  if (e.empty()) return NAN;
  std::nth_element(e.begin(), e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2), e.end());
  return e[e.size() / 2];
}

}  // namespace

TEST(RealScans, Vlp16VelodyneScanGives16RingsAndEveryMrptPoint) {
  auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservationVelodyneScan>(
      firstObservation("test_velodyne_VLP16.rawlog"));
  ASSERT_TRUE(obs);
  ASSERT_EQ(obs->point_cloud.size(), 0u);  // as shipped: packets only
  auto copy = *obs;
  copy.generatePointCloud();  // MRPT's own cloud, default parameters (what map insertion uses)
  const std::size_t mrpt_points = copy.point_cloud.size();
  EXPECT_EQ(mrpt_points, 11305u);

  LidarFrame f;
  const auto st = ObservationConverter().convert(*obs, f);
  EXPECT_EQ(f.rows(), 16);
  // MRPT 2.5.8 decodes one of the two firings per VLP-16 block: 0.4 deg steps -> 900 columns.
  EXPECT_EQ(f.cols(), 900);
  EXPECT_EQ(f.sourcePointCount(), mrpt_points);
  EXPECT_EQ(st.input_points, mrpt_points);
  EXPECT_EQ(st.invalid + st.outside_fov, 0u);
  EXPECT_EQ(st.pixels_set + st.hidden, mrpt_points);
  EXPECT_TRUE(
      std::all_of(f.point_pixel.begin(), f.point_pixel.end(), [](int p) { return p >= 0; }));
  EXPECT_TRUE(f.has_intensity);
  EXPECT_GT(f.timestamp_ns, INT64_C(1519600000000000000));  // 2018-02-26
  // Rows are ordered by elevation: ring 0 at +15 deg ... ring 15 at -15 deg, 2 deg apart.
  for (int r = 0; r < 16; r++) {
    SCOPED_TRACE(r);
    EXPECT_NEAR(medianElevationDeg(f, r), 15.0 - 2.0 * r, 0.3);
    EXPECT_GT(cv::countNonZero(f.valid.row(r)), 100);
  }
  // Few collisions and no systematic holes: the grid matches the firing rate.
  EXPECT_LT(st.hidden, mrpt_points / 50);
  // Single-pixel holes between two returns on the lowest ring (the ground) would be a grid
  // that is finer than the data; 1800 columns on this cloud leave every other column empty.
  auto isolatedHoles = [](const LidarFrame& fr, int row) {
    int holes = 0;
    for (int c = 1; c + 1 < fr.cols(); c++)
      holes += !fr.isValid(row, c) && fr.isValid(row, c - 1) && fr.isValid(row, c + 1);
    return holes;
  };
  EXPECT_GT(cv::countNonZero(f.valid.row(15)), f.cols() / 2);
  EXPECT_LT(isolatedHoles(f, 15), f.cols() / 50);

  // With the sensor preset the grid is the VLP-16's own 1800 columns.
  LidarFrame g;
  ObservationConverter(preset("vlp-16.ini")).convert(*obs, g);
  EXPECT_EQ(g.cols(), 1800);
  EXPECT_EQ(g.sourcePointCount(), mrpt_points);
  EXPECT_GT(isolatedHoles(g, 15), g.cols() / 5);
}

TEST(RealScans, Vlp16RotatingScanMatchesTheVelodyneConversion) {
  auto rot = std::dynamic_pointer_cast<mrpt::obs::CObservationRotatingScan>(
      firstObservation("rot_scan_velodyne.rawlog"));
  ASSERT_TRUE(rot);
  LidarFrame fr;
  EXPECT_THROW(ObservationConverter().convert(*rot, fr), dynobj::mrptio::ConversionError);
  const auto st = ObservationConverter(preset("vlp-16.ini")).convert(*rot, fr);
  EXPECT_EQ(st.input_points, 11305u);
  EXPECT_EQ(fr.rows(), 16);

  auto velo = firstObservation("test_velodyne_VLP16.rawlog");
  LidarFrame fv;
  ObservationConverter(preset("vlp-16.ini")).convert(*velo, fv);
  // The same pixel in both frames sees the same return (MRPT 2.5 carries no per-laser azimuth
  // offsets for rotating scans, so allow one column of slack).
  std::size_t matched = 0, total = 0;
  for (int r = 0; r < 16; r++)
    for (int c = 0; c < fv.cols(); c++) {
      if (!fv.isValid(r, c)) continue;
      total++;
      for (int dc = -1; dc <= 1; dc++) {
        const int cc = (c + dc + fr.cols()) % fr.cols();
        if (fr.isValid(r, cc) && std::abs(fr.range(r, cc) - fv.range(r, c)) < 0.05f) {
          matched++;
          break;
        }
      }
    }
  EXPECT_GT(static_cast<double>(matched) / static_cast<double>(total), 0.95)
      << matched << " of " << total;
  for (int r = 0; r < 16; r++) EXPECT_NEAR(medianElevationDeg(fr, r), 15.0 - 2.0 * r, 0.3);
}

TEST(RealScans, RgbdRangeScanOrganizedPathKeepsAllPoints) {
  auto obs = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(
      firstObservation("tests_rgbd.rawlog"));
  ASSERT_TRUE(obs);
  obs->load();
  ASSERT_TRUE(obs->hasPoints3D);
  const std::size_t n = obs->points3D_x.size();
  ASSERT_EQ(obs->points3D_idxs_x.size(), n);
  LidarFrame f;
  const auto st = ObservationConverter().convert(*obs, f);
  EXPECT_EQ(f.rows(), 480);
  EXPECT_EQ(f.cols(), 640);
  EXPECT_EQ(f.sourcePointCount(), n);
  EXPECT_EQ(st.pixels_set + st.hidden + st.invalid, n);
  // Each valid pixel shows the point whose index says it belongs there.
  for (int r = 0; r < f.rows(); r += 7)
    for (int c = 0; c < f.cols(); c += 7) {
      if (!f.isValid(r, c)) continue;
      const auto i = static_cast<std::size_t>(f.source_index(r, c));
      ASSERT_EQ(obs->points3D_idxs_y[i], r);
      ASSERT_EQ(obs->points3D_idxs_x[i], c);
    }
}
