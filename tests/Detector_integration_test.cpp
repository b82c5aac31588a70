// SPDX-License-Identifier: BSD-3-Clause
// The whole detector on simulated sequences (cross-module: sim -> rawlog -> mrpt -> core).
#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/eval/Metrics.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/PointCloudFilterAdapter.h>
#include <dynobj/mrptio/PoseConversion.h>
#include <dynobj/mrptio/RawlogFrameSource.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <dynobj/sim/LidarSimulator.h>
#include <gtest/gtest.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cstdio>

using namespace dynobj;

namespace {

const std::string kSample = std::string(DYNOBJ_SOURCE_DIR) + "/rawlogs/hall-small/hall-small";

struct RunResult {
  eval::Confusion confusion;
  std::vector<double> motion_errors;  ///< |translation error| of the ego-motion per frame [m]
  int ego_ok = 0, frames = 0;
};

enum class Motion { Own, GroundTruth, StandingStill };

/// Runs the detector over the committed sample with its own ego-motion, or given the ground-truth
/// motion, or given a wrong one (identity: the robot stood still, while it really moves).
RunResult runSample(Motion motion) {
  RunResult out;
  const auto truth = io::LabelFile::read(kSample + ".gt.labels");
  const auto poses = io::readPoseFile(kSample + ".gt.tum", io::PoseFormat::Tum);
  dynobj::mrptio::RawlogFrameSource stream(
      kSample + ".rawlog", dynobj::mrptio::ObservationConverter(), {"LIDAR", 0, 1000000});
  core::DynamicObjectDetector det;
  dynobj::mrptio::Frame item;
  const io::TimedPose* prev = nullptr;
  while (stream.next(item)) {
    const auto& f = item.frame;
    const auto* pose = io::findPose(poses, f.timestamp_ns);
    EXPECT_NE(pose, nullptr);
    std::optional<Eigen::Isometry3d> true_motion, given;
    if (prev) true_motion = prev->pose.inverse() * pose->pose;
    if (prev && motion == Motion::GroundTruth) given = true_motion;
    if (prev && motion == Motion::StandingStill) given = Eigen::Isometry3d::Identity();
    const auto& r = det.process(f, given);
    if (true_motion && r.ego_motion.ok) {
      out.ego_ok++;
      out.motion_errors.push_back(
          (true_motion->translation() - r.ego_motion.motion.translation()).norm());
    }
    cv::Mat_<std::uint8_t> gt(f.rows(), f.cols(), std::uint8_t{0});
    for (auto px : truth.sweeps.at(static_cast<std::size_t>(out.frames)).pixels)
      gt(static_cast<int>(px) / f.cols(), static_cast<int>(px) % f.cols()) = 255;
    out.confusion.add(r.dynamic, gt, f.valid);
    prev = pose;
    out.frames++;
  }
  std::printf("sample: precision %.4f, recall %.4f, %d of %d frames with ego-motion\n",
              out.confusion.precision().value_or(-1), out.confusion.recall().value_or(-1),
              out.ego_ok, out.frames);
  return out;
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

// Bounds within 10 % (relative) of the measured figures; a detector change that moves them must
// re-measure (and say so in its commit), not loosen them silently.
TEST(Detector, HallSampleWithIntensityEgoMotion) {
  const RunResult r = runSample(Motion::Own);
  ASSERT_EQ(r.frames, 40);
  // Measured: precision 1.000, recall 0.599 (the first ~7 frames cannot have detections: the
  // sliding window and the confirmation must fill first).
  EXPECT_GE(r.confusion.precision().value_or(0), 0.95);
  EXPECT_GE(r.confusion.recall().value_or(0), 0.56);
  EXPECT_GE(r.ego_ok, 39);                   // every frame but the first
  EXPECT_LT(median(r.motion_errors), 0.03);  // ORB ego-motion vs ground truth, per frame
}

TEST(Detector, HallSampleWithExternalEgoMotion) {
  // Measured with the ground-truth motion: precision 1.000, recall 0.607.
  const RunResult r = runSample(Motion::GroundTruth);
  EXPECT_GE(r.confusion.precision().value_or(0), 0.95);
  EXPECT_GE(r.confusion.recall().value_or(0), 0.57);
  // The external motion is really used: told that the robot stood still (it walks at ~1 m/s), the
  // detector takes the static scene for moving (measured: precision 0.019).
  const RunResult still = runSample(Motion::StandingStill);
  EXPECT_LT(still.confusion.precision().value_or(0), 0.1);
}

TEST(Detector, StaticSceneFlagsAlmostNothing) {
  const sim::LidarSimulator simu(sim::Scenario::fromYamlFile(
      std::string(DYNOBJ_SHARE_DIR) + "/scenarios/static.yaml", DYNOBJ_SHARE_DIR,
      {{"frames", "40"}, {"sensor", "sensors/os0-64-512.ini"}}));
  core::DynamicObjectDetector det;
  std::size_t flagged = 0, points = 0;
  for (int k = 0; k < 40; k++) {
    const auto sweep = simu.simulate(k);
    const auto& r = det.process(sweep.frame);
    flagged += static_cast<std::size_t>(cv::countNonZero(r.dynamic));
    points += sweep.frame.validCount();
  }
  // Measured: 0 of 993,885 points flagged; the bound is 1e-5 (~10 points; the 300-sweep `static`
  // of docs/accuracy.md flags 0.002 %).
  const double share = static_cast<double>(flagged) / static_cast<double>(points);
  std::printf("static: %zu of %zu points flagged (%.6f)\n", flagged, points, share);
  EXPECT_LE(share, 1e-5);
}

TEST(Detector, ResetForgetsEverything) {
  const sim::LidarSimulator simu(sim::Scenario::fromYamlFile(
      std::string(DYNOBJ_SHARE_DIR) + "/scenarios/hall.yaml", DYNOBJ_SHARE_DIR,
      {{"frames", "12"}, {"sensor", "sensors/os0-64-512.ini"}}));
  core::DynamicObjectDetector a, b;
  for (int k = 0; k < 12; k++) a.process(simu.simulate(k).frame);
  a.reset();
  for (int k = 0; k < 3; k++) {  // after reset, a behaves exactly like a fresh detector
    const auto f = simu.simulate(k).frame;
    const auto& ra = a.process(f);
    const cv::Mat_<std::uint8_t> da = ra.dynamic.clone();
    const auto& rb = b.process(f);
    EXPECT_EQ(cv::countNonZero(da != rb.dynamic), 0);
    EXPECT_EQ(ra.frame_index, rb.frame_index);
  }
}

TEST(Detector, SecondThreadGivesTheSameResults) {
  // [pipeline] threads = 2 runs the ego-motion beside ground, foreground and clustering: every
  // frame's masks, ego-motion and objects must be those of threads = 1, bit for bit.
  const sim::LidarSimulator simu(sim::Scenario::fromYamlFile(
      std::string(DYNOBJ_SHARE_DIR) + "/scenarios/crossing.yaml", DYNOBJ_SHARE_DIR,
      {{"frames", "30"}, {"sensor", "sensors/os0-64-512.ini"}}));
  core::DetectorParams one, two;
  one.pipeline.threads = 1;
  two.pipeline.threads = 2;
  core::DynamicObjectDetector a(one), b(two);
  int dynamic = 0;
  for (int k = 0; k < 30; k++) {
    const auto f = simu.simulate(k).frame;
    const core::DetectionResult ra = a.process(f).clone();
    const core::DetectionResult& rb = b.process(f);
    EXPECT_EQ(cv::countNonZero(ra.dynamic != rb.dynamic), 0) << "frame " << k;
    EXPECT_EQ(cv::countNonZero(ra.features != rb.features), 0) << "frame " << k;
    EXPECT_EQ(cv::countNonZero(ra.ground != rb.ground), 0) << "frame " << k;
    EXPECT_TRUE(ra.ego_motion.motion.matrix() == rb.ego_motion.motion.matrix()) << "frame " << k;
    EXPECT_EQ(ra.ego_motion.source, rb.ego_motion.source);
    ASSERT_EQ(ra.objects.size(), rb.objects.size()) << "frame " << k;
    for (std::size_t o = 0; o < ra.objects.size(); o++) {
      EXPECT_EQ(ra.objects[o].id, rb.objects[o].id);
      EXPECT_EQ(ra.objects[o].dynamic, rb.objects[o].dynamic);
      EXPECT_EQ(ra.objects[o].points, rb.objects[o].points);
    }
    dynamic += cv::countNonZero(ra.dynamic);
  }
  EXPECT_GT(dynamic, 0);  // the comparison covered movers, not only empty masks
}

TEST(Detector, BehindMrptsPointCloudFilterInterface) {
  const sim::LidarSimulator simu(sim::Scenario::fromYamlFile(
      std::string(DYNOBJ_SHARE_DIR) + "/scenarios/hall.yaml", DYNOBJ_SHARE_DIR,
      {{"frames", "30"}, {"sensor", "sensors/os0-64-512.ini"}}));
  dynobj::mrptio::PointCloudFilterAdapter adapter(simu.scenario().sensor);
  mrpt::maps::CPointCloudFilterBase& filter = adapter;  // used through MRPT's interface
  std::size_t flagged = 0, correct = 0;
  for (int k = 0; k < 30; k++) {
    const auto sweep = simu.simulate(k);
    mrpt::maps::CSimplePointsMap cloud;
    std::vector<int> pixel;  // pixel of each point, to score against ground truth
    for (int r = 0; r < sweep.frame.rows(); r++)
      for (int c = 0; c < sweep.frame.cols(); c++)
        if (sweep.frame.isValid(r, c)) {
          const cv::Vec3f& p = sweep.frame.xyz(r, c);
          cloud.insertPoint(p[0], p[1], p[2]);
          pixel.push_back(r * sweep.frame.cols() + c);
        }
    const std::size_t before = cloud.size();
    std::vector<bool> del;
    mrpt::maps::CPointCloudFilterBase::TExtraFilterParams extra;
    extra.out_deletion_mask = &del;
    const auto pose = dynobj::mrptio::toCPose3D(sweep.sensor_pose);
    filter.filter(&cloud, dynobj::mrptio::fromUnixNs(sweep.timestamp_ns), pose, &extra);
    ASSERT_EQ(del.size(), before);
    const auto n = static_cast<std::size_t>(std::count(del.begin(), del.end(), true));
    EXPECT_EQ(cloud.size(), before - n);  // deleted exactly the flagged points
    for (std::size_t i = 0; i < del.size(); i++)
      if (del[i]) {
        flagged++;
        correct += sweep.dynamic(pixel[i] / sweep.frame.cols(), pixel[i] % sweep.frame.cols()) != 0;
      }
  }
  // No intensity through this interface: features come from the range image. Measured: 1461
  // points flagged, 1389 (95 %) on moving actors; the test asserts that most of what it removes
  // is moving people.
  std::printf("adapter: %zu points flagged, %zu on moving actors\n", flagged, correct);
  EXPECT_GT(flagged, 0u);
  EXPECT_GE(static_cast<double>(correct), 0.8 * static_cast<double>(flagged));
}
