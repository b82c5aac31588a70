// SPDX-License-Identifier: BSD-3-Clause
// Export -> import of the KTH DynamicMap layout: same frames, points, poses, timestamps.
#include <dynobj/mapclean/KthExport.h>
#include <dynobj/mapclean/ScanSource.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "FrameFixture.h"

namespace mc = dynobj::mapclean;
namespace fs = std::filesystem;

TEST(KthExport, ExportThenImportRoundTrips) {
  const fs::path dir = mc::test::tmpPath("kth");
  fs::remove_all(dir);
  // Points on the tiny sensor's pixel-centre rays, so re-projection finds the same pixels.
  const auto ray = [](int row, int col, float range) {
    const double el = (15.0 - 10.0 * row) * M_PI / 180.0;
    const double az = -M_PI + (col + 0.5) * 2 * M_PI / 8;
    return cv::Vec3f(static_cast<float>(range * std::cos(el) * std::cos(az)),
                     static_cast<float>(range * std::cos(el) * std::sin(az)),
                     static_cast<float>(range * std::sin(el)));
  };
  std::vector<dynobj::core::LidarFrame> frames = {
      mc::test::tinyFrame({{{0, 1}, ray(0, 1, 4)}, {{2, 5}, ray(2, 5, 7)}, {{3, 7}, ray(3, 7, 2)}},
                          1000),
      mc::test::tinyFrame({{{1, 0}, ray(1, 0, 3)}, {{1, 4}, ray(1, 4, 9)}}, 2000)};
  std::vector<Eigen::Isometry3d> poses(2, Eigen::Isometry3d::Identity());
  poses[1].translation() = Eigen::Vector3d(1, 2, 0.5);
  poses[1].linear() = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  {
    mc::KthExporter ex(dir.string(), true);
    for (std::size_t i = 0; i < frames.size(); i++) {
      cv::Mat_<std::uint8_t> gt(4, 8, std::uint8_t{0});
      gt(1, 4) = 255;
      ex.add(frames[i], poses[i], &gt);
    }
    EXPECT_FALSE(fs::exists(dir));  // only after close()
    ex.close();
  }
  ASSERT_TRUE(fs::exists(dir / "pcd" / "000001.pcd"));
  const auto gt = mc::readPcd((dir / "gt_cloud.pcd").string());
  ASSERT_EQ(gt.points.size(), 5u);
  EXPECT_EQ(gt.points[4].intensity, 1.f);  // frame 1, pixel (1, 4)
  EXPECT_EQ(gt.points[3].intensity, 0.f);

  mc::ScanSourceOptions o;
  o.sensor = mc::test::tinySensor();
  auto src = mc::openScanSource(dir.string(), o);
  mc::Scan s;
  for (std::size_t i = 0; i < frames.size(); i++) {
    ASSERT_TRUE(src->next(s));
    EXPECT_EQ(s.frame.validCount(), frames[i].validCount());
    EXPECT_EQ(s.frame.timestamp_ns, frames[i].timestamp_ns);
    ASSERT_TRUE(s.viewpoint);
    EXPECT_TRUE(s.viewpoint->isApprox(poses[i], 1e-6));
    for (int r = 0; r < 4; r++)
      for (int c = 0; c < 8; c++) {
        ASSERT_EQ(s.frame.isValid(r, c), frames[i].isValid(r, c)) << r << "," << c;
        if (frames[i].isValid(r, c)) {
          EXPECT_LT(cv::norm(s.frame.xyz(r, c) - frames[i].xyz(r, c)), 1e-5);
        }
      }
  }
  EXPECT_FALSE(src->next(s));
  EXPECT_THROW(mc::KthExporter(dir.string(), false), std::runtime_error);  // an existing one is not
}
