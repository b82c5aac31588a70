// SPDX-License-Identifier: BSD-3-Clause
// drop / split on the unorganized LiDAR classes (CObservationVelodyneScan, CObservationPointCloud),
// the counterpart of RangeScanTagging_unittest.cpp's organized-scan tests: exactly the flagged
// points leave, the rest keep their order and per-point fields, stock insertion sees the rest,
// split gets the removed ones, and through DynamicObjectFilter the classes take the same path.
#include <dynobj/core/SensorModel.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/DynamicObjectFilter.h>
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/ObservationTagging.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>

#include <cmath>

#include "MapInsertion.h"

namespace dm = dynobj::mrptio;
namespace mobs = mrpt::obs;

namespace {

std::shared_ptr<mobs::CObservationVelodyneScan> vlp16() {
  dm::RawlogReader reader("/usr/share/mrpt/datasets/test_velodyne_VLP16.rawlog");
  dm::RawlogEntry e;
  EXPECT_TRUE(reader.next(e));
  auto v = std::dynamic_pointer_cast<mobs::CObservationVelodyneScan>(e.observations().at(0));
  EXPECT_TRUE(v);
  return v;
}

std::vector<std::uint8_t> everyThird(std::size_t n) {
  std::vector<std::uint8_t> m(n, 0);
  for (std::size_t i = 0; i < n; i += 3) m[i] = 1;
  return m;
}

std::shared_ptr<mobs::CObservationPointCloud> ringCloud() {
  auto o = std::make_shared<mobs::CObservationPointCloud>();
  auto pc = std::make_shared<mrpt::maps::CSimplePointsMap>();
  for (int i = 0; i < 360; i++)
    pc->insertPoint(static_cast<float>(5 * std::cos(i * M_PI / 180)),
                    static_cast<float>(5 * std::sin(i * M_PI / 180)),
                    0.1f * static_cast<float>(i % 8));
  o->pointcloud = pc;
  o->sensorLabel = "CLOUD";
  return o;
}

}  // namespace

TEST(PointTagging, VelodyneDropRemovesExactlyTheFlaggedPointsAndSplitGetsThem) {
  auto v = vlp16();
  v->generatePointCloud();
  const auto before = v->point_cloud;
  const std::size_t n = before.size();
  ASSERT_EQ(n, 11305u);
  const auto mask = everyThird(n);
  mrpt::maps::CSimplePointsMap removed;
  const auto st = dm::dropDynamic(*v, mask, &removed);
  const std::size_t flagged = (n + 2) / 3;
  EXPECT_EQ(st.points_removed, flagged);
  ASSERT_EQ(v->point_cloud.size(), n - flagged);
  ASSERT_EQ(removed.size(), flagged);
  EXPECT_EQ(v->point_cloud.intensity.size(), n - flagged);
  EXPECT_EQ(v->point_cloud.laser_id.size(), v->point_cloud.laser_id.empty() ? 0 : n - flagged);
  for (std::size_t i = 0, k = 0; i < n; i++) {  // the kept ones, in order, with their fields
    if (mask[i]) continue;
    ASSERT_EQ(v->point_cloud.x[k], before.x[i]);
    ASSERT_EQ(v->point_cloud.intensity[k], before.intensity[i]);
    k++;
  }
  float x, y, z;
  removed.getPoint(1, x, y, z);  // the second flagged point is input point 3
  EXPECT_EQ(x, before.x[3]);
  EXPECT_EQ(dynobj::test::insertedPoints(*v), n - flagged);      // what a stock point map inserts
  EXPECT_THROW(dm::dropDynamic(*v, mask), dm::ConversionError);  // the mask no longer fits
}

TEST(PointTagging, PointCloudDropRemovesExactlyTheFlaggedPointsAndSplitGetsThem) {
  auto o = ringCloud();
  const auto mask = everyThird(360);
  mrpt::maps::CSimplePointsMap removed;
  const auto st = dm::dropDynamic(*o, mask, &removed);
  EXPECT_EQ(st.points_removed, 120u);
  ASSERT_EQ(o->pointcloud->size(), 240u);
  ASSERT_EQ(removed.size(), 120u);
  float x, y, z;
  o->pointcloud->getPoint(0, x, y, z);  // input point 1
  EXPECT_FLOAT_EQ(z, 0.1f);
  removed.getPoint(2, x, y, z);  // input point 6
  EXPECT_FLOAT_EQ(z, 0.6f);
  EXPECT_THROW(dm::dropDynamic(*o, everyThird(10)), dm::ConversionError);
}

TEST(PointTagging, FilterSplitsVelodyneScansAndPointCloudsThroughTheClassTable) {
  dm::DynamicObjectFilter::Options opts;
  opts.mode = dm::FilterMode::Split;
  opts.sensor = dynobj::io::readSensorModel(std::string(DYNOBJ_SHARE_DIR) + "/sensors/vlp-16.ini");
  dm::DynamicObjectFilter filter(opts);
  std::vector<mobs::CObservation::Ptr> extra;
  mobs::CObservation::Ptr velo = vlp16(), cloud = ringCloud();
  ASSERT_NE(filter.filter(velo, &extra), nullptr);
  ASSERT_NE(filter.filter(cloud, &extra), nullptr);
  EXPECT_EQ(filter.summary().lidar, 2u);
  EXPECT_EQ(filter.summary().points, 11305u + 360u);
  ASSERT_EQ(extra.size(), 2u);  // one "<label>_DYNAMIC" cloud per observation (here: empty)
  EXPECT_EQ(extra[0]->sensorLabel, velo->sensorLabel + "_DYNAMIC");
  EXPECT_EQ(extra[1]->sensorLabel, "CLOUD_DYNAMIC");
  // mark needs a label channel: these classes pass through with a warning.
  opts.mode = dm::FilterMode::Mark;
  dm::DynamicObjectFilter marker(opts);
  EXPECT_EQ(marker.filter(velo), nullptr);
  EXPECT_EQ(marker.summary().passed_through, 1u);
}
