// SPDX-License-Identifier: BSD-3-Clause
// Converters on tiny hand-built observations, including every malformed case.
#include <dynobj/mrptio/ObservationConverter.h>
#include <gtest/gtest.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation2DRangeScan.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationRotatingScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <cmath>
#include <limits>

using dynobj::core::LidarFrame;
using dynobj::core::SensorModel;
using dynobj::mrptio::ConversionError;
using dynobj::mrptio::ObservationConverter;
namespace mobs = mrpt::obs;

namespace {

constexpr double kDeg = M_PI / 180.0;

/// 4 beams (+15, +5, -5, -15 deg), 8 columns.
SensorModel tinySensor() {
  SensorModel s;
  s.model = "tiny";
  s.rows = 4;
  s.cols = 8;
  s.elevation_top = 15 * kDeg;
  s.elevation_bottom = -15 * kDeg;
  return s;
}

/// Expects convert() to throw a ConversionError whose message contains `needle`.
void expectError(const ObservationConverter& conv, const mobs::CObservation& obs,
                 const std::string& needle) {
  LidarFrame f;
  try {
    conv.convert(obs, f);
    FAIL() << "expected ConversionError containing '" << needle << "'";
  } catch (const ConversionError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

/// A 4 x 8 organized scan with one point at pixel (1, 2) and one at (3, 7).
mobs::CObservation3DRangeScan tinyRangeScan() {
  mobs::CObservation3DRangeScan o;
  o.sensorLabel = "LIDAR";
  o.hasRangeImage = true;
  o.rangeImage_setSize(4, 8);
  o.rangeImage.fill(0);
  o.range_is_depth = false;
  o.hasPoints3D = true;
  o.resizePoints3DVectors(2);
  o.points3D_x = {1.0f, 0.0f};
  o.points3D_y = {2.0f, 5.0f};
  o.points3D_z = {0.5f, -1.0f};
  o.points3D_idxs_x = {2, 7};
  o.points3D_idxs_y = {1, 3};
  return o;
}

}  // namespace

TEST(ObservationConverter, RangeScan3DOrganizedPath) {
  auto o = tinyRangeScan();
  o.hasIntensityImage = true;
  cv::Mat_<std::uint8_t> img(4, 8, std::uint8_t{0});
  img(1, 2) = 77;
  o.intensityImage = mrpt::img::CImage(img, mrpt::img::DEEP_COPY);
  LidarFrame f;
  const auto st = ObservationConverter().convert(o, f);
  EXPECT_EQ(st.pixels_set, 2u);
  EXPECT_EQ(f.rows(), 4);
  EXPECT_EQ(f.cols(), 8);
  EXPECT_EQ(f.source_index(1, 2), 0);
  EXPECT_EQ(f.source_index(3, 7), 1);
  EXPECT_FLOAT_EQ(f.intensity(1, 2), 77.0f);
  EXPECT_FLOAT_EQ(f.range(3, 7), std::sqrt(26.0f));
  EXPECT_TRUE(f.has_intensity);
}

TEST(ObservationConverter, RangeScan3DMalformed) {
  const ObservationConverter conv;
  {
    auto o = tinyRangeScan();
    o.points3D_idxs_y[1] = 4;  // row 4 of a 4-row image
    expectError(conv, o, "outside its 4x8 image");
  }
  {
    auto o = tinyRangeScan();
    o.points3D_y.pop_back();
    expectError(conv, o, "different lengths");
  }
  {
    auto o = tinyRangeScan();
    o.points3D_idxs_x.clear();
    o.points3D_idxs_y.clear();
    expectError(conv, o, "points3D_idxs_x/y");
  }
  {
    auto o = tinyRangeScan();
    o.hasIntensityImage = true;
    o.intensityImage =
        mrpt::img::CImage(cv::Mat_<std::uint8_t>(3, 8, std::uint8_t{1}), mrpt::img::DEEP_COPY);
    expectError(conv, o, "intensityImage is 3x8");
  }
  {
    mobs::CObservation3DRangeScan o;
    o.sensorLabel = "X";
    expectError(conv, o, "neither a range image nor an intensity image");
  }
  {
    auto o = tinyRangeScan();
    o.hasPoints3D = false;
    expectError(conv, o, "sensor model");
  }
  {
    auto o = tinyRangeScan();
    o.hasPoints3D = false;
    o.range_is_depth = true;
    expectError(ObservationConverter(tinySensor()), o, "range_is_depth");
  }
  {
    auto o = tinyRangeScan();
    SensorModel s = tinySensor();
    s.cols = 16;
    expectError(ObservationConverter(s), o, "is 4x8 but the sensor model 'tiny' is 4x16");
  }
  {
    auto o = tinyRangeScan();
    o.points3D_x[0] = std::numeric_limits<float>::quiet_NaN();
    LidarFrame f;
    const auto st = ObservationConverter().convert(o, f);  // a NaN point is skipped and counted
    EXPECT_EQ(st.invalid, 1u);
    EXPECT_EQ(f.point_pixel[0], -1);
  }
}

TEST(ObservationConverter, RangeScan3DWithoutPointsUsesTheSensorModel) {
  auto o = tinyRangeScan();
  o.hasPoints3D = false;
  o.rangeUnits = 0.01f;
  o.rangeImage(2, 4) = 1000;  // 10 m at -5 deg elevation, azimuth of column 4's centre (22.5 deg)
  LidarFrame f;
  ObservationConverter(tinySensor()).convert(o, f);
  ASSERT_EQ(f.validCount(), 1u);
  ASSERT_TRUE(f.isValid(2, 4));
  const cv::Vec3f p = f.xyz(2, 4);
  EXPECT_NEAR(p[2], 10 * std::sin(-5 * kDeg), 1e-4);
  EXPECT_NEAR(std::atan2(p[1], p[0]), 22.5 * kDeg, 1e-5);
  EXPECT_FALSE(f.has_intensity);
}

TEST(ObservationConverter, PointCloudNeedsSensorAndKeepsIntensity) {
  auto pc = std::make_shared<mrpt::maps::CPointsMapXYZI>();
  pc->insertPointFast(1, 0, 0);
  pc->insertPointFast(0, 5, 0);
  pc->insertPointFast(std::numeric_limits<float>::quiet_NaN(), 0, 0);
  pc->setPointIntensity(0, 0.25f);
  pc->setPointIntensity(1, 0.75f);
  mobs::CObservationPointCloud o;
  o.sensorLabel = "PC";
  o.pointcloud = pc;
  expectError(ObservationConverter(), o, "without a sensor model");  // no ring, no laser order
  LidarFrame f;
  const auto st = ObservationConverter(tinySensor()).convert(o, f);
  EXPECT_EQ(st.invalid, 1u);
  EXPECT_EQ(st.pixels_set, 2u);
  EXPECT_TRUE(f.has_intensity);
  EXPECT_FLOAT_EQ(f.intensity(2, 4), 0.25f);  // (1,0,0): Eq. (1) pixel (2, 4)
  EXPECT_FLOAT_EQ(f.intensity(2, 6), 0.75f);  // (0,5,0): azimuth 90 deg -> column 6

  mobs::CObservationPointCloud plain;
  plain.pointcloud = std::make_shared<mrpt::maps::CSimplePointsMap>();
  plain.pointcloud->insertPoint(3, 0, 0);
  ObservationConverter(tinySensor()).convert(plain, f);
  EXPECT_FALSE(f.has_intensity);  // documented fallback: features use the range image

  mobs::CObservationPointCloud null_pc;
  expectError(ObservationConverter(tinySensor()), null_pc, "null");
  mobs::CObservationPointCloud empty_pc;
  empty_pc.pointcloud = std::make_shared<mrpt::maps::CSimplePointsMap>();
  expectError(ObservationConverter(tinySensor()), empty_pc, "empty");
}

TEST(ObservationConverter, RotatingScanDocumentedAzimuthConvention) {
  mobs::CObservationRotatingScan o;
  o.sensorLabel = "ROT";
  o.rowCount = 4;
  o.columnCount = 8;
  o.rangeImage.setZero(4, 8);
  o.intensityImage.setZero(4, 8);
  o.rangeResolution = 0.01;
  o.startAzimuth = -M_PI;
  o.azimuthSpan = 2 * M_PI;  // counter-clockwise, the class's documented convention
  o.lidarModel = "generic";
  o.rangeImage(0, 6) = 500;  // scan row 0 = laser 0; column 6 centre = -pi + 6.5/8*2pi = 112.5 deg
  o.intensityImage(0, 6) = 9;
  SensorModel s = tinySensor();
  s.beam_elevations = {-5 * kDeg, 15 * kDeg, 5 * kDeg, -15 * kDeg};  // laser 0 = third row
  LidarFrame f;
  ObservationConverter(s).convert(o, f);
  ASSERT_EQ(f.validCount(), 1u);
  ASSERT_TRUE(f.isValid(2, 6));
  EXPECT_FLOAT_EQ(f.intensity(2, 6), 9.0f);
  EXPECT_NEAR(f.range(2, 6), 5.0f, 1e-5);
  const cv::Vec3f p = f.xyz(2, 6);
  EXPECT_NEAR(std::atan2(p[1], p[0]), 112.5 * kDeg, 1e-5);

  SensorModel wrong = tinySensor();
  wrong.rows = 5;
  wrong.elevation_bottom = -25 * kDeg;
  expectError(ObservationConverter(wrong), o, "has 4 rows but the sensor model");
  o.intensityImage.setZero(3, 8);
  expectError(ObservationConverter(s), o, "intensityImage is 3x8");
}

TEST(ObservationConverter, VelodynePointCloudRowsFollowCalibration) {
  mobs::CObservationVelodyneScan o;
  o.sensorLabel = "VELO";
  o.calibration.laser_corrections.resize(4);
  const double elev[4] = {-15, 5, -5, 15};  // laser 0 is the lowest beam
  for (int i = 0; i < 4; i++) o.calibration.laser_corrections[i].verticalCorrection = elev[i];
  auto& pc = o.point_cloud;
  auto add = [&](double az_deg, int laser, double r, std::uint8_t inten) {
    const double el = elev[laser] * kDeg, az = az_deg * kDeg;
    pc.x.push_back(static_cast<float>(r * std::cos(el) * std::cos(az)));
    pc.y.push_back(static_cast<float>(r * std::cos(el) * std::sin(az)));
    pc.z.push_back(static_cast<float>(r * std::sin(el)));
    pc.intensity.push_back(inten);
    pc.laser_id.push_back(static_cast<std::int16_t>(laser));
  };
  add(0.1, 0, 10, 50);           // lowest beam -> row 3
  add(90.1, 3, 4, 60);           // highest beam -> row 0
  SensorModel s = tinySensor();  // 8 columns instead of the default 1800
  LidarFrame f;
  ObservationConverter(s).convert(o, f);
  EXPECT_EQ(f.rows(), 4);
  EXPECT_EQ(f.cols(), 8);
  EXPECT_TRUE(f.isValid(3, 4));
  EXPECT_TRUE(f.isValid(0, 6));
  EXPECT_FLOAT_EQ(f.intensity(0, 6), 60.0f);

  pc.laser_id[1] = 9;
  expectError(ObservationConverter(s), o, "laser_id 9");
  pc.laser_id.pop_back();
  expectError(ObservationConverter(s), o, "different lengths");
  mobs::CObservationVelodyneScan empty;
  empty.calibration = o.calibration;
  expectError(ObservationConverter(), empty, "empty");
  mobs::CObservationVelodyneScan nocal;
  expectError(ObservationConverter(), nocal, "no laser calibration");
}

TEST(ObservationConverter, UnsupportedClassIsRejected) {
  mobs::CObservation2DRangeScan scan;
  scan.sensorLabel = "LASER2D";
  EXPECT_FALSE(ObservationConverter::isLidarObservation(scan));
  EXPECT_TRUE(ObservationConverter::isLidarObservation(mobs::CObservation3DRangeScan()));
  expectError(ObservationConverter(), scan, "CObservation2DRangeScan 'LASER2D'");
}
