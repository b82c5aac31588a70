// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mrptio/DynamicObjectFilter.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/io/lazy_load_path.h>
#include <mrpt/system/filesystem.h>

#include "FullScan.h"

namespace dm = dynobj::mrptio;
namespace mobs = mrpt::obs;
using dynobj::test::fullScan;

TEST(DynamicObjectFilter, ExternallyStoredScansPassThroughWithAWarning) {
  auto scan = std::make_shared<mobs::CObservation3DRangeScan>(fullScan());
  const std::string dir = dynobj::testing::scratchPath("_ext");
  mrpt::system::createDirectory(dir);
  mrpt::io::setLazyLoadPathBase(dir + "/");
  scan->points3D_convertToExternalStorage("pts.bin", dir + "/");
  ASSERT_TRUE(scan->points3D_isExternallyStored());
  dm::DynamicObjectFilter filter({dm::FilterMode::Drop, "", std::nullopt, {}});
  mrpt::obs::CObservation::Ptr obs = scan;
  EXPECT_EQ(filter.filter(obs), nullptr);
  EXPECT_TRUE(scan->points3D_isExternallyStored());  // untouched: its external file is not ours
  EXPECT_EQ(filter.summary().passed_through, 1u);
  ASSERT_EQ(filter.summary().warnings.size(), 1u);
  EXPECT_NE(filter.summary().warnings.begin()->first.find("de-externalize"), std::string::npos);
  mrpt::io::setLazyLoadPathBase(".");
}

TEST(DynamicObjectFilter, NonLidarAndOtherLabelsPassThroughUntouched) {
  dm::DynamicObjectFilter filter({dm::FilterMode::Drop, "LIDAR", std::nullopt, {}});
  auto other = std::make_shared<mobs::CObservation3DRangeScan>(fullScan());
  other->sensorLabel = "OTHER";
  const auto before = other->points3D_x;
  mrpt::obs::CObservation::Ptr obs = other;
  EXPECT_EQ(filter.filter(obs), nullptr);
  EXPECT_EQ(other->points3D_x, before);
  EXPECT_EQ(filter.summary().observations, 1u);
  EXPECT_EQ(filter.summary().lidar, 0u);
  EXPECT_THROW(dm::parseFilterMode("erase"), std::invalid_argument);
  EXPECT_EQ(std::string(dm::toString(dm::parseFilterMode("split"))), "split");
}
