// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/SphericalProjection.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>

using dynobj::core::LidarFrame;
using dynobj::core::PointCloud;
using dynobj::core::SensorModel;
using dynobj::core::SphericalProjection;

namespace {

constexpr double kDeg = M_PI / 180.0;

/// 4 beams at +15, +5, -5, -15 deg, 8 columns: beta_up = 20 deg, beta_fov = 40 deg.
SensorModel tinySensor() {
  SensorModel s;
  s.model = "tiny";
  s.rows = 4;
  s.cols = 8;
  s.elevation_top = 15 * kDeg;
  s.elevation_bottom = -15 * kDeg;
  return s;
}

/// Unit vector at azimuth az and elevation el, times range r.
void pointAt(double az, double el, double r, float& x, float& y, float& z) {
  x = static_cast<float>(r * std::cos(el) * std::cos(az));
  y = static_cast<float>(r * std::cos(el) * std::sin(az));
  z = static_cast<float>(r * std::sin(el));
}

}  // namespace

TEST(SphericalProjection, FovEdgesOfUniformSensor) {
  const SensorModel s = tinySensor();
  EXPECT_NEAR(s.fovUp(), 20 * kDeg, 1e-12);
  EXPECT_NEAR(s.fovSpan(), 40 * kDeg, 1e-12);
}

TEST(SphericalProjection, Eq1HandComputedPixels) {
  const SphericalProjection p(tinySensor());
  int r = 0, c = 0;
  // (1,0,0): v = (20 - 0) / 40 * 4 = 2, u = (0 + pi) / 2pi * 8 = 4
  ASSERT_TRUE(p.pixelOf(1, 0, 0, r, c));
  EXPECT_EQ(r, 2);
  EXPECT_EQ(c, 4);
  // Elevation 15 deg, azimuth +90 deg: v = 5/40*4 = 0.5 -> 0; u = 1.5pi/2pi*8 = 6
  float x, y, z;
  pointAt(M_PI / 2, 15 * kDeg, 10, x, y, z);
  ASSERT_TRUE(p.pixelOf(x, y, z, r, c));
  EXPECT_EQ(r, 0);
  EXPECT_EQ(c, 6);
  // Elevation -12 deg, azimuth -90 deg: v = 32/40*4 = 3.2 -> 3; u = 0.5pi/2pi*8 = 2
  pointAt(-M_PI / 2, -12 * kDeg, 3, x, y, z);
  ASSERT_TRUE(p.pixelOf(x, y, z, r, c));
  EXPECT_EQ(r, 3);
  EXPECT_EQ(c, 2);
  // Elevation +4.9 deg: v = 15.1/40*4 = 1.51 -> 1; azimuth 100 deg: u = 280/360*8 = 6.2 -> 6
  pointAt(100 * kDeg, 4.9 * kDeg, 7, x, y, z);
  ASSERT_TRUE(p.pixelOf(x, y, z, r, c));
  EXPECT_EQ(r, 1);
  EXPECT_EQ(c, 6);
}

TEST(SphericalProjection, AzimuthWrapsAtPlusMinusPi) {
  const SphericalProjection p(tinySensor());
  EXPECT_EQ(p.columnOf(-1.0, 0.0), 0);   // atan2(+0, -1) = +pi -> u = 8 -> wraps to 0
  EXPECT_EQ(p.columnOf(-1.0, -0.0), 0);  // atan2(-0, -1) = -pi -> u = 0
  EXPECT_EQ(p.columnOf(std::cos(M_PI - 0.01), std::sin(M_PI - 0.01)), 7);
  EXPECT_EQ(p.columnOf(std::cos(-M_PI + 0.01), std::sin(-M_PI + 0.01)), 0);
  EXPECT_EQ(p.columnOf(1.0, -1e-9), 3);  // just right of straight ahead
  EXPECT_EQ(p.columnOf(1.0, 0.0), 4);
}

TEST(SphericalProjection, VerticalFovEdges) {
  const SensorModel s = tinySensor();
  const SphericalProjection p(s);
  EXPECT_EQ(p.rowOfElevation(s.fovUp()), 0);                // top edge belongs to row 0
  EXPECT_EQ(p.rowOfElevation(s.fovUp() - s.fovSpan()), 3);  // bottom edge to the last row
  EXPECT_EQ(p.rowOfElevation(s.fovUp() + 1e-9), -1);
  EXPECT_EQ(p.rowOfElevation(s.fovUp() - s.fovSpan() - 1e-9), -1);
  EXPECT_EQ(p.rowOfElevation(10 * kDeg), 1);  // exactly on the row 0/1 boundary -> lower row
  int r = 0, c = 0;
  float x, y, z;
  pointAt(0.3, 20.5 * kDeg, 5, x, y, z);
  EXPECT_FALSE(p.pixelOf(x, y, z, r, c));
  EXPECT_EQ(r, -1);
  pointAt(0.3, -20.5 * kDeg, 5, x, y, z);
  EXPECT_FALSE(p.pixelOf(x, y, z, r, c));
  pointAt(0.3, 19.9 * kDeg, 5, x, y, z);
  EXPECT_TRUE(p.pixelOf(x, y, z, r, c));
  EXPECT_EQ(r, 0);
}

TEST(SphericalProjection, BeamTableUsesNearestBeam) {
  SensorModel s = tinySensor();
  s.beam_elevations = {0 * kDeg, 10 * kDeg, -5 * kDeg, 2 * kDeg};  // laser-id order
  ASSERT_NO_THROW(s.validate());
  EXPECT_EQ(s.laserToRow(), (std::vector<int>{2, 0, 3, 1}));
  const SphericalProjection p(s);
  // Rows: 10 | 2 | 0 | -5; edges 14, 6, 1, -2.5, -7.5
  EXPECT_EQ(p.rowOfElevation(13.9 * kDeg), 0);
  EXPECT_EQ(p.rowOfElevation(14.1 * kDeg), -1);
  EXPECT_EQ(p.rowOfElevation(5 * kDeg), 1);
  EXPECT_EQ(p.rowOfElevation(1.5 * kDeg), 1);
  EXPECT_EQ(p.rowOfElevation(0.5 * kDeg), 2);
  EXPECT_EQ(p.rowOfElevation(-3 * kDeg), 3);
  EXPECT_EQ(p.rowOfElevation(-7.4 * kDeg), 3);
  EXPECT_EQ(p.rowOfElevation(-7.6 * kDeg), -1);
}

TEST(SphericalProjection, NearestPointWinsAndAllPointsStayMapped) {
  const SphericalProjection p(tinySensor());
  PointCloud cloud;
  cloud.push_back(5, 0, 0, 50);  // pixel (2,4), far
  cloud.push_back(3, 0, 0, 30);  // same pixel, nearer: shown
  cloud.push_back(4, 0, 0, 40);  // same pixel, middle
  cloud.push_back(std::numeric_limits<float>::quiet_NaN(), 0, 0, 1);
  cloud.push_back(0, 0, 0, 1);   // origin = invalid (MRPT convention)
  cloud.push_back(0, 0, 10, 1);  // straight up: outside FOV
  LidarFrame f;
  const auto st = p.project(cloud, f);
  EXPECT_EQ(st.input_points, 6u);
  EXPECT_EQ(st.pixels_set, 1u);
  EXPECT_EQ(st.hidden, 2u);
  EXPECT_EQ(st.invalid, 2u);
  EXPECT_EQ(st.outside_fov, 1u);
  EXPECT_EQ(f.source_index(2, 4), 1);
  EXPECT_FLOAT_EQ(f.range(2, 4), 3.0f);
  EXPECT_FLOAT_EQ(f.intensity(2, 4), 30.0f);
  EXPECT_TRUE(f.has_intensity);
  const int px = 2 * 8 + 4;
  EXPECT_EQ(f.point_pixel, (std::vector<std::int32_t>{px, px, px, -1, -1, -1}));
  cv::Mat_<std::uint8_t> mask(4, 8, std::uint8_t{0});
  mask(2, 4) = 1;
  EXPECT_EQ(f.pointMaskFromPixelMask(mask), (std::vector<std::uint8_t>{1, 1, 1, 0, 0, 0}));
}

TEST(SphericalProjection, BadIntensityIsZeroedAndCounted) {
  const SphericalProjection p(tinySensor());
  PointCloud cloud;
  cloud.push_back(5, 0, 0, std::numeric_limits<float>::infinity());
  cloud.push_back(0, 5, 0, -3);
  LidarFrame f;
  const auto st = p.project(cloud, f);
  EXPECT_EQ(st.bad_intensity, 2u);
  EXPECT_EQ(st.pixels_set, 2u);
  EXPECT_FLOAT_EQ(f.intensity(2, 4), 0.0f);
}

TEST(SphericalProjection, RoundTripPointListFrameIndicesLosesNothing) {
  SensorModel s;  // OS0-64 defaults: 64 x 1024
  const SphericalProjection p(s);
  const auto elev = s.rowElevations();
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> range(0.5, 40.0), jitter(-0.3, 0.3);
  std::uniform_int_distribution<int> row(0, s.rows - 1), col(0, s.cols - 1);
  PointCloud cloud;
  for (int i = 0; i < 20000; i++) {  // many collisions on purpose (~26% of pixels hit twice)
    const int r = row(rng), c = col(rng);
    const double az = -M_PI + (c + 0.5 + jitter(rng)) * 2 * M_PI / s.cols;
    const double el = elev[static_cast<std::size_t>(r)] + jitter(rng) * (s.fovSpan() / s.rows);
    float x, y, z;
    pointAt(az, el, range(rng), x, y, z);
    cloud.push_back(x, y, z, static_cast<float>(i));
  }
  LidarFrame f;
  const auto st = p.project(cloud, f);
  EXPECT_EQ(st.invalid + st.outside_fov, 0u);
  EXPECT_EQ(st.pixels_set + st.hidden, cloud.size());
  ASSERT_EQ(f.sourcePointCount(), cloud.size());
  for (std::size_t i = 0; i < cloud.size(); i++) {
    const int px = f.point_pixel[i];
    ASSERT_GE(px, 0) << "point " << i << " lost";
    const int r = px / f.cols(), c = px % f.cols();
    ASSERT_TRUE(f.isValid(r, c));
    const int shown = f.source_index(r, c);
    ASSERT_EQ(f.point_pixel[static_cast<std::size_t>(shown)], px);
    const float ri = std::hypot(std::hypot(cloud.x[i], cloud.y[i]), cloud.z[i]);
    EXPECT_LE(f.range(r, c), ri + 1e-5f);  // the shown point is the nearest
    if (static_cast<std::size_t>(shown) == i) {
      EXPECT_FLOAT_EQ(f.intensity(r, c), cloud.intensity[i]);
    }
  }
}

TEST(SphericalProjection, OrganizedPathKeepsGivenPixels) {
  const SphericalProjection p(tinySensor());
  PointCloud cloud;
  cloud.push_back(1, 2, 3, 7, 3, 5);  // placed where the cloud says, not where Eq. (1) would
  cloud.push_back(2, 0, 0, 9, 0, 0);
  cloud.push_back(1, 0, 0, 8, 0, 0);  // same pixel, nearer
  LidarFrame f;
  const auto st = p.organize(cloud, f);
  EXPECT_EQ(st.pixels_set, 2u);
  EXPECT_EQ(st.hidden, 1u);
  EXPECT_EQ(f.source_index(3, 5), 0);
  EXPECT_EQ(f.source_index(0, 0), 2);
  EXPECT_FLOAT_EQ(f.range(3, 5), std::sqrt(14.0f));
  EXPECT_EQ(f.point_pixel, (std::vector<std::int32_t>{29, 0, 0}));
}

TEST(SphericalProjection, SecondPassOnlyFillsPixelsTheFirstLeftEmpty) {
  const SphericalProjection p(tinySensor());
  PointCloud cloud;
  cloud.push_back(3, 0, 0, 7, 0, 0);  // first pass, 3 m
  cloud.push_back(1, 0, 0, 8, 0, 0);  // second pass, nearer, same pixel: does not take it
  cloud.push_back(2, 0, 0, 9, 1, 1);  // second pass, a pixel the first left empty: takes it
  const std::vector<std::uint8_t> second = {0, 1, 1};
  LidarFrame f;
  const auto st = p.organize(cloud, f, &second);
  EXPECT_EQ(st.pixels_set, 2u);
  EXPECT_EQ(st.hidden, 1u);
  EXPECT_EQ(st.second_pass, 2u);
  EXPECT_EQ(f.source_index(0, 0), 0);
  EXPECT_FLOAT_EQ(f.range(0, 0), 3.0f);
  EXPECT_EQ(f.source_index(1, 1), 2);
  EXPECT_EQ(f.point_pixel, (std::vector<std::int32_t>{0, 0, 9}));  // every point mapped
  const std::vector<std::uint8_t> wrong_size = {0, 1};
  EXPECT_THROW(p.organize(cloud, f, &wrong_size), std::invalid_argument);
}

TEST(SphericalProjection, OrganizedPathRejectsPixelsOutsideImage) {
  const SphericalProjection p(tinySensor());
  PointCloud cloud;
  cloud.push_back(1, 0, 0, 1, 0, 0);
  cloud.push_back(1, 0, 0, 1, 4, 0);  // row 4 of a 4-row image
  LidarFrame f;
  try {
    p.organize(cloud, f);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("point 1"), std::string::npos) << e.what();
  }
}

TEST(SphericalProjection, MismatchedCloudVectorsAreRejected) {
  const SphericalProjection p(tinySensor());
  PointCloud cloud;
  cloud.push_back(1, 0, 0, 1);
  cloud.intensity.push_back(2);
  LidarFrame f;
  try {
    p.project(cloud, f);
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("intensity"), std::string::npos) << e.what();
  }
}

namespace {

/// The reference rule pixelOf must reproduce: Eq. (1) through asin and atan2.
bool exactPixel(const SphericalProjection& p, double x, double y, double z, int& row, int& col) {
  const double r = std::sqrt(x * x + y * y + z * z);
  row = p.rowOfElevation(std::asin(std::clamp(z / r, -1.0, 1.0)));
  col = row < 0 ? -1 : p.columnOf(x, y);
  return row >= 0;
}

/// Oracle: pixelOf against exactPixel on random directions and on directions placed at small
/// fractions of a degree from every row and column edge (where the fast path hands over).
void expectSameAsExact(const SensorModel& s) {
  const SphericalProjection p(s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> az(-M_PI, M_PI), el(-M_PI / 2, M_PI / 2), u01(0, 1);
  std::vector<std::array<double, 2>> dirs;  // (azimuth, elevation)
  for (int i = 0; i < 200000; i++) dirs.push_back({az(rng), el(rng)});
  const double col_w = 2 * M_PI / s.cols;
  const double offsets[] = {0, 1e-12, -1e-12, 1e-9, -1e-9, 5e-6, -5e-6, 2e-5, -2e-5, 1e-4, -1e-4};
  for (int c = 0; c <= s.cols; c++)
    for (double o : offsets) dirs.push_back({-M_PI + c * col_w + o, el(rng) * 0.2});
  std::vector<double> edges;
  const auto e = s.rowElevations();
  edges.push_back(s.fovUp());
  for (std::size_t k = 1; k < e.size(); k++) edges.push_back(0.5 * (e[k - 1] + e[k]));
  edges.push_back(s.fovUp() - s.fovSpan());
  for (double edge : edges)
    for (double o : offsets) dirs.push_back({az(rng), edge + o});
  int mismatches = 0;
  for (const auto& [a, b] : dirs) {
    const double rr = 0.5 + 60 * u01(rng);
    const double x = rr * std::cos(b) * std::cos(a), y = rr * std::cos(b) * std::sin(a),
                 z = rr * std::sin(b);
    int r1, c1, r2, c2;
    const bool in1 = p.pixelOf(x, y, z, r1, c1), in2 = exactPixel(p, x, y, z, r2, c2);
    if (in1 != in2 || (in1 && (r1 != r2 || c1 != c2))) {
      if (mismatches++ < 5)
        ADD_FAILURE() << s.model << ": az " << a << " el " << b << " fast (" << r1 << ", " << c1
                      << ") exact (" << r2 << ", " << c2 << ")";
    }
  }
  EXPECT_EQ(mismatches, 0) << s.model << ": of " << dirs.size() << " directions";
}

}  // namespace

TEST(SphericalProjection, PixelOfMatchesAsinAtan2OnEveryEdgeUniformSensors) {
  for (int cols : {8, 512, 1024, 2048}) {
    SensorModel s = tinySensor();
    s.model = "uniform-" + std::to_string(cols);
    s.rows = 64;
    s.cols = cols;
    s.elevation_top = 45 * kDeg;
    s.elevation_bottom = -45 * kDeg;
    expectSameAsExact(s);
  }
}

TEST(SphericalProjection, PixelOfMatchesAsinAtan2OnEveryEdgeBeamTable) {
  SensorModel s = tinySensor();
  s.model = "table";
  s.rows = 6;
  s.cols = 2048;
  s.beam_elevations = {10 * kDeg, 9 * kDeg, 2 * kDeg, 1.9 * kDeg, -20 * kDeg, -24.8 * kDeg};
  expectSameAsExact(s);
}

TEST(SphericalProjection, PixelOfMatchesAsinAtan2OnADomeBeyondNinetyDegrees) {
  SensorModel s = tinySensor();  // edges half a spacing beyond +-90 deg
  s.model = "dome";
  s.rows = 32;
  s.cols = 1024;
  s.elevation_top = 90 * kDeg;
  s.elevation_bottom = -90 * kDeg;
  expectSameAsExact(s);
  const SphericalProjection p(s);
  int r, c;
  ASSERT_TRUE(p.pixelOf(0.001, 0, 10, r, c));  // straight up: the top row
  EXPECT_EQ(r, 0);
  ASSERT_TRUE(p.pixelOf(0.001, 0, -10, r, c));
  EXPECT_EQ(r, 31);
}
