// SPDX-License-Identifier: BSD-3-Clause
// markDynamic, dropDynamic and restoreDynamic on organized range scans.
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/ObservationTagging.h>
#include <dynobj/mrptio/RangeScanLayout.h>
#include <gtest/gtest.h>
#include <mrpt/obs/TPixelLabelInfo.h>

#include "FullScan.h"
#include "MapInsertion.h"
#include "SerializationRoundTrip.h"

using namespace dynobj;
namespace dm = dynobj::mrptio;
namespace mobs = mrpt::obs;
using dynobj::test::fullScan;

namespace {

cv::Mat_<std::uint8_t> someMask() {
  cv::Mat_<std::uint8_t> m(8, 64, std::uint8_t{0});
  m(cv::Rect(10, 2, 4, 3)).setTo(255);  // 12 pixels
  m(7, 63) = 255;                       // 13
  return m;
}

}  // namespace

TEST(RangeScanTagging, MarkSetsTheDynamicBitAndKeepsOtherLabels) {
  auto o = fullScan();
  o.pixelLabels = std::make_shared<mobs::TPixelLabelInfo<1>>();
  o.pixelLabels->setSize(8, 64);
  o.pixelLabels->setLabelName(0, "ground");
  o.pixelLabels->setLabel(7, 0, 0);
  const auto st = dm::markDynamic(o, someMask());
  EXPECT_EQ(st.pixels, 13u);
  const int idx = o.pixelLabels->checkLabelNameExistence("dynamic");
  ASSERT_EQ(idx, 1);
  EXPECT_TRUE(o.pixelLabels->checkLabel(7, 0, 0));  // the user's label is untouched
  int set = 0;
  for (int r = 0; r < 8; r++)
    for (int c = 0; c < 64; c++) set += o.pixelLabels->checkLabel(r, c, 1);
  EXPECT_EQ(set, 13);
  EXPECT_EQ(o.points3D_x.size(), 512u);             // geometry untouched
  auto back = dynobj::test::serializeRoundTrip(o);  // labels are serialized
  EXPECT_TRUE(back->pixelLabels->checkLabel(3, 11, 1));
  // Marking again with another mask moves the bit (no stale labels).
  cv::Mat_<std::uint8_t> other(8, 64, std::uint8_t{0});
  other(0, 0) = 1;
  dm::markDynamic(o, other);
  EXPECT_FALSE(o.pixelLabels->checkLabel(3, 11, 1));
  EXPECT_TRUE(o.pixelLabels->checkLabel(0, 0, 1));
}

TEST(RangeScanTagging, DropRemovesExactlyTheFlaggedPointsAndRestoreGivesThemBack) {
  const auto original = fullScan();
  auto o = original;
  const auto st = dm::dropDynamic(o, someMask());
  EXPECT_EQ(st.points_removed, 13u);
  EXPECT_EQ(o.points3D_x.size(), 512u - 13u);
  EXPECT_EQ(o.points3D_idxs_y.size(), o.points3D_x.size());
  EXPECT_EQ(dynobj::test::insertedPoints(o), 512u - 13u);  // what a stock point map inserts
  EXPECT_EQ(o.rangeImage(3, 11), 0);
  EXPECT_EQ(dm::rangeLayer(o, dm::kDynamicLayer)(3, 11), original.rangeImage(3, 11));
  for (std::size_t i = 0; i < o.points3D_x.size(); i++)
    EXPECT_FALSE(someMask()(o.points3D_idxs_y[i], o.points3D_idxs_x[i]));

  auto back = dynobj::test::serializeRoundTrip(
      o);  // through serialization (and MRPT 2.5.8's transposed layers)
  const auto rs = dm::restoreDynamic(*back);
  EXPECT_EQ(rs.points_restored, 13u);
  EXPECT_EQ(back->points3D_x.size(), 512u);
  EXPECT_TRUE(back->rangeImageOtherLayers.count(dm::kDynamicLayer) == 0);
  for (int r = 0; r < 8; r++)
    for (int c = 0; c < 64; c++)
      ASSERT_EQ(back->rangeImage(r, c), original.rangeImage(r, c)) << r << "," << c;
  core::LidarFrame a, b;
  dm::ObservationConverter().convert(original, a);
  dm::ObservationConverter().convert(*back, b);
  for (int r = 0; r < 8; r++)
    for (int c = 0; c < 64; c++)
      EXPECT_LT(cv::norm(a.xyz(r, c) - b.xyz(r, c)), 2e-3) << r << "," << c;  // range units: 1 mm
}

TEST(RangeScanTagging, BadInputsAreErrors) {
  auto o = fullScan();
  cv::Mat_<std::uint8_t> wrong(4, 64, std::uint8_t{0});
  EXPECT_THROW(dm::markDynamic(o, wrong), dm::ConversionError);
  mobs::CObservation3DRangeScan empty;
  EXPECT_THROW(dm::dropDynamic(empty, someMask()), dm::ConversionError);
  auto full = fullScan();  // every label bit taken by other names
  full.pixelLabels = std::make_shared<mobs::TPixelLabelInfo<1>>();
  full.pixelLabels->setSize(8, 64);
  for (unsigned i = 0; i < 8; i++) full.pixelLabels->setLabelName(i, "l" + std::to_string(i));
  try {
    dm::markDynamic(full, someMask());
    FAIL();
  } catch (const dm::ConversionError& e) {
    EXPECT_NE(std::string(e.what()).find("label bits are taken"), std::string::npos);
  }
  auto none = fullScan();
  EXPECT_EQ(dm::restoreDynamic(none).points_restored, 0u);  // nothing was dropped: no-op
}
