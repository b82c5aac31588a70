// SPDX-License-Identifier: BSD-3-Clause
// frame -> CObservation3DRangeScan (organized layout) -> serialized -> read -> frame.
#include <dynobj/core/SphericalProjection.h>
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/RangeScanLayout.h>
#include <gtest/gtest.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/serialization/CArchive.h>

#include <random>

#include "SerializationRoundTrip.h"

using namespace dynobj;
namespace mobs = mrpt::obs;

namespace {

core::LidarFrame randomFrame(unsigned seed, int rows, int cols) {
  core::SensorModel s;
  s.rows = rows;
  s.cols = cols;
  s.max_range = 120;  // needs 2 mm range units
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> az(-M_PI, M_PI), el(-0.7, 0.7), r(0.5, 110),
      inten(0, 3000);
  core::PointCloud cloud;
  for (int i = 0; i < rows * cols / 2; i++) {
    const double a = az(rng), e = el(rng), d = r(rng);
    cloud.push_back(static_cast<float>(d * std::cos(e) * std::cos(a)),
                    static_cast<float>(d * std::cos(e) * std::sin(a)),
                    static_cast<float>(d * std::sin(e)),
                    static_cast<float>(std::round(inten(rng))));
  }
  core::LidarFrame f;
  core::SphericalProjection(s).project(cloud, f);
  return f;
}

}  // namespace

TEST(RangeScanLayout, RoundTripThroughSerializationKeepsEveryReturn) {
  const core::LidarFrame a = randomFrame(7, 16, 64);
  mobs::CObservation3DRangeScan obs;
  dynobj::mrptio::frameToRangeScan(a, obs);
  EXPECT_FLOAT_EQ(obs.rangeUnits, 0.002f);
  EXPECT_FALSE(obs.range_is_depth);
  EXPECT_EQ(obs.points3D_x.size(), a.validCount());
  auto back = dynobj::test::serializeRoundTrip(obs);
  ASSERT_TRUE(back);
  // MRPT 2.5.8 reads other layers with rows/cols swapped: rangeLayer() must undo it.
  const auto layer = dynobj::mrptio::intensityLayer(*back);
  ASSERT_EQ(layer.rows, 16);
  ASSERT_EQ(layer.cols, 64);

  core::LidarFrame b;
  dynobj::mrptio::ObservationConverter().convert(*back, b);
  ASSERT_EQ(b.rows(), 16);
  ASSERT_EQ(b.cols(), 64);
  EXPECT_EQ(b.validCount(), a.validCount());
  for (int r = 0; r < 16; r++)
    for (int c = 0; c < 64; c++) {
      ASSERT_EQ(a.isValid(r, c), b.isValid(r, c));
      if (!a.isValid(r, c)) continue;
      EXPECT_EQ(a.xyz(r, c), b.xyz(r, c));  // points are stored as floats: exact
      EXPECT_FLOAT_EQ(a.intensity(r, c), b.intensity(r, c));
      EXPECT_NEAR(back->rangeImage(r, c) * back->rangeUnits, a.range(r, c), 0.0011);
    }
}

TEST(RangeScanLayout, StockPointMapInsertsExactlyTheValidPixels) {
  const core::LidarFrame a = randomFrame(3, 8, 32);
  mobs::CObservation3DRangeScan obs;
  dynobj::mrptio::frameToRangeScan(a, obs);
  mrpt::maps::CSimplePointsMap map;
  map.insertionOptions.minDistBetweenLaserPoints = 0;
  ASSERT_TRUE(map.insertObservation(obs));
  EXPECT_EQ(map.size(), a.validCount());
}

TEST(RangeScanLayout, FrameWithoutIntensityWritesNoIntensity) {
  core::LidarFrame a = randomFrame(5, 4, 16);
  a.has_intensity = false;
  mobs::CObservation3DRangeScan obs;
  dynobj::mrptio::frameToRangeScan(a, obs);
  EXPECT_FALSE(obs.hasIntensityImage);
  EXPECT_TRUE(dynobj::mrptio::intensityLayer(obs).empty());
}
