// SPDX-License-Identifier: BSD-3-Clause
// Human labels -> per-point truth: hand-made boxes and points with exact expected labels.
#include <dynobj/eval/PointTruth.h>
#include <dynobj/eval/SequenceMetrics.h>
#include <dynobj/io/FormatError.h>
#include <dynobj/io/SemanticKittiLabel.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace dynobj;
using eval::PointLabel;

namespace {

namespace fs = std::filesystem;

/// A folder under the test's temporary directory, removed with everything in it at the end.
struct TempFolder {
  explicit TempFolder(const std::string& name)
      : path(fs::path(::testing::TempDir()) / ("dynobj-eval-truth-" + name)) {
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempFolder() { fs::remove_all(path); }
  std::string file(const std::string& name) const { return (path / name).string(); }
  fs::path path;
};

eval::TruthBox box(int track, const std::string& cls, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& size, double yaw = 0) {
  eval::TruthBox b;
  b.track = track;
  b.cls = cls;
  b.size = size;
  b.pose = Eigen::Translation3d(centre) * Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
  return b;
}

core::PointCloud cloud(const std::vector<Eigen::Vector3d>& pts) {
  core::PointCloud c;
  for (const auto& p : pts)
    c.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z()));
  return c;
}

std::vector<std::int64_t> stamps(std::size_t n) {
  std::vector<std::int64_t> s;
  for (std::size_t k = 0; k < n; k++) s.push_back(static_cast<std::int64_t>(k) * 100000000);
  return s;
}

/// Ten sweeps at 10 Hz of a sensor standing still: track 1 drives along +x at 2 m/s (a 4 x 2 x
/// 1.5 m car centred 0.75 m up), track 2 is parked, track 3 is seen in one sweep only.
std::unique_ptr<eval::BoxTruth> streetScene(std::function<bool(const Eigen::Vector3d&)> fov) {
  std::vector<std::vector<eval::TruthBox>> boxes(10);
  for (int k = 0; k < 10; k++) {
    boxes[k].push_back(box(1, "Car", {10 + 0.2 * k, 0, 0.75}, {4, 2, 1.5}));
    boxes[k].push_back(box(2, "Van", {0, 8, 1.0}, {5, 2, 2}, M_PI / 2));
  }
  boxes[5].push_back(box(3, "Pedestrian", {5, -5, 0.9}, {0.8, 0.8, 1.8}));
  auto t = std::make_unique<eval::BoxTruth>(std::move(boxes), eval::BoxTruthParams{},
                                            std::move(fov), "street");
  t->setSensorPoses(std::vector<Eigen::Isometry3d>(10, Eigen::Isometry3d::Identity()), stamps(10));
  return t;
}

}  // namespace

TEST(BoxTruth, InsideBandGroundAndParkedPointsOfHandMadeBoxes) {
  const auto truth = streetScene(nullptr);
  // Sweep 4: the moving car is centred at x = 10.8 (x 8.8..12.8, y -1..1, z 0..1.5).
  const core::PointCloud pts = cloud({
      {10.8, 0.0, 0.75},   // 0: inside the moving car
      {12.7, 0.9, 1.4},    // 1: inside, near a corner
      {12.9, 0.0, 0.75},   // 2: 0.1 m beyond its front: the band, unknown
      {10.8, 0.0, 0.1},    // 3: its lowest 0.2 m (wheels, the road under it): unknown
      {10.8, 0.0, -0.15},  // 4: the road just under it, within the band: unknown
      {13.2, 0.0, 0.75},   // 5: 0.4 m beyond its front: static
      {0.0, 8.0, 1.0},     // 6: inside the parked van: static
      {1.4, 8.0, 1.0},     // 7: 0.4 m beside the van (2 m wide across x): static
      {30.0, 5.0, 0.0},    // 8: a wall: static
  });
  const eval::SweepTruth t = truth->truthOf(4, pts);
  const std::vector<PointLabel> want{PointLabel::Moving,  PointLabel::Moving,  PointLabel::Unknown,
                                     PointLabel::Unknown, PointLabel::Unknown, PointLabel::Static,
                                     PointLabel::Static,  PointLabel::Static,  PointLabel::Static};
  EXPECT_EQ(t.label, want);
  EXPECT_EQ(t.object, (std::vector<std::int32_t>{1, 1, -1, -1, -1, -1, -1, -1, -1}));
  EXPECT_EQ(truth->className(1), "Car");
}

TEST(BoxTruth, MotionJudgedOverTheWindowFromTheTrajectory) {
  const auto truth = streetScene(nullptr);
  ASSERT_EQ(truth->tracks().size(), 3u);
  for (const eval::TrackMotion& m : truth->tracks()) {
    ASSERT_EQ(m.sweeps.size(), m.track == 3 ? 1u : 10u);
    for (std::size_t i = 0; i < m.sweeps.size(); i++) {
      if (m.track == 1) {
        EXPECT_NEAR(m.speed[i], 2.0, 1e-9);
        EXPECT_EQ(m.state[i], PointLabel::Moving);
      } else if (m.track == 2) {
        EXPECT_NEAR(m.speed[i], 0.0, 1e-9);
        EXPECT_EQ(m.state[i], PointLabel::Static);
      } else {  // seen once: no trajectory, its points unknown
        EXPECT_TRUE(std::isnan(m.speed[i]));
        EXPECT_EQ(m.state[i], PointLabel::Unknown);
      }
    }
  }
  const eval::SweepTruth t = truth->truthOf(5, cloud({{5, -5, 0.9}, {5, -5, 2.0}}));
  EXPECT_EQ(t.label[0], PointLabel::Unknown);  // inside the pedestrian seen once
  EXPECT_EQ(t.label[1], PointLabel::Unknown);  // in its band
}

TEST(BoxTruth, SensorPosesTellAParkedCarFromOneDrivenAlongside) {
  // The sensor drives along +x at 2 m/s. Track 1 keeps its place in the sensor frame (it drives
  // alongside at the same speed: moving); track 2 slides back by 0.2 m a sweep in the sensor
  // frame (parked: static).
  std::vector<std::vector<eval::TruthBox>> boxes(10);
  std::vector<Eigen::Isometry3d> poses;
  for (int k = 0; k < 10; k++) {
    boxes[k].push_back(box(1, "Car", {0, -4, 0.75}, {4, 2, 1.5}));
    boxes[k].push_back(box(2, "Car", {20 - 0.2 * k, 4, 0.75}, {4, 2, 1.5}));
    poses.push_back(Eigen::Isometry3d(Eigen::Translation3d(0.2 * k, 0, 0)));
  }
  eval::BoxTruth truth(std::move(boxes), {}, nullptr, "alongside");
  truth.setSensorPoses(poses, stamps(10));
  const eval::SweepTruth t = truth.truthOf(3, cloud({{0, -4, 0.75}, {19.4, 4, 0.75}}));
  EXPECT_EQ(t.label[0], PointLabel::Moving);
  EXPECT_EQ(t.label[1], PointLabel::Static);
}

TEST(BoxTruth, PointsOutsideTheAnnotatedViewAreUnknown) {
  const auto truth = streetScene([](const Eigen::Vector3d& p) { return p.x() > 0; });
  const eval::SweepTruth t = truth->truthOf(0, cloud({{10, 0, 0.75}, {-10, 0, 0.75}, {20, 3, 0}}));
  EXPECT_EQ(t.label,
            (std::vector<PointLabel>{PointLabel::Moving, PointLabel::Unknown, PointLabel::Static}));
}

TEST(BoxTruth, KittiLabelsAndCalibrationPlaceTheBoxInTheVelodyneFrame) {
  // Camera axes from Velodyne ones as on the KITTI car (x right = -y, y down = -z, z ahead = x),
  // the camera 0.27 m ahead of the LiDAR; R_rect identity; a 1000 x 500 px image.
  TempFolder dir("kitti");
  {
    std::ofstream c(dir.file("calib.txt"));
    c << "P2: 500 0 500 0 0 500 250 0 0 0 1 0\n"
      << "R_rect 1 0 0 0 1 0 0 0 1\n"
      << "Tr_velo_cam 0 -1 0 0 0 0 -1 0 1 0 0 -0.27\n";
    std::ofstream l(dir.file("label.txt"));
    // A car driving away at 2 m/s: bottom centre 1.7 m below the camera (y down), 10 m ahead,
    // h 1.5, w 1.6, l 4, ry = 0 (its length along the camera's x, i.e. across the road).
    for (int k = 0; k < 10; k++)
      l << k << " 0 Car 0 0 0 0 0 0 0 1.5 1.6 4 0 1.7 " << 10 + 0.2 * k << " 0\n";
    l << "3 -1 DontCare -1 -1 -10 0 0 10 10 -1 -1 -1 -1000 -1000 -1000 -10\n";
  }
  const auto truth =
      eval::BoxTruth::fromKitti(dir.file("label.txt"), dir.file("calib.txt"), {}, 1000, 500);
  truth->setSensorPoses(std::vector<Eigen::Isometry3d>(10, Eigen::Isometry3d::Identity()),
                        stamps(10));
  // Sweep 0: centre at camera (0, 0.95, 10) = Velodyne (10.27, 0, -0.95); 4 m long along y.
  const eval::SweepTruth t = truth->truthOf(0, cloud({
                                                   {10.27, 0, -0.95},   // centre: moving
                                                   {10.27, 1.9, -0.5},  // near its end: moving
                                                   {11.2, 0, -0.95},    // 0.13 m beyond its back
                                                   {-5, 0, 0},          // behind the camera
                                                   {2, 20, 0},          // outside the image
                                               }));
  EXPECT_EQ(t.label,
            (std::vector<PointLabel>{PointLabel::Moving, PointLabel::Moving, PointLabel::Unknown,
                                     PointLabel::Unknown, PointLabel::Unknown}));
  ASSERT_EQ(truth->tracks().size(), 1u);  // the DontCare row is left out
  EXPECT_EQ(truth->className(0), "Car");
}

TEST(BoxTruth, MalformedInputsNameTheFileAndLine) {
  TempFolder dir("bad");
  {
    std::ofstream(dir.file("short.txt")) << "0 0 Car 0 0 0 0 0 0 0 1.5 1.6\n";
    std::ofstream(dir.file("calib.txt")) << "P2: 1 2 3\n";
    std::ofstream(dir.file("boxes.csv")) << "sweep,track,class,x,y,z,length,width,height,yaw\n"
                                         << "0,1,car,1,2,3,4,0,1,0\n";
  }
  try {
    io::readKittiTrackingLabels(dir.file("short.txt"));
    FAIL() << "no error";
  } catch (const io::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("short.txt:1"), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::readKittiCalib(dir.file("calib.txt")), io::FormatError);
  try {
    io::readBoxTracks(dir.file("boxes.csv"));
    FAIL() << "no error";
  } catch (const io::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("boxes.csv:2"), std::string::npos) << e.what();
  }
  EXPECT_THROW(eval::openPointTruth(dir.file("short.txt"), ""), eval::EvaluationError);  // calib?
}

TEST(BoxTruth, GenericBoxTrackFileInTheSensorFrame) {
  TempFolder dir("csv");
  {
    std::ofstream f(dir.file("boxes.csv"));
    f << "# a walker crossing\nsweep,track,class,x,y,z,length,width,height,yaw\n";
    for (int k = 0; k < 10; k++)
      f << k << ",4,person,5," << -2 + 0.15 * k << ",0.9,0.6,0.6,1.8," << M_PI / 2 << "\n";
  }
  auto truth = eval::openPointTruth(dir.file("boxes.csv"), "");
  ASSERT_TRUE(truth->needsPoses());
  truth->setSensorPoses(std::vector<Eigen::Isometry3d>(10, Eigen::Isometry3d::Identity()),
                        stamps(10));
  const eval::SweepTruth t = truth->truthOf(0, cloud({{5, -2, 1.2}, {5, 2, 1.2}}));
  EXPECT_EQ(t.label[0], PointLabel::Moving);  // 1.5 m/s
  EXPECT_EQ(t.object[0], 4);
  EXPECT_EQ(t.label[1], PointLabel::Static);
  EXPECT_EQ(truth->className(4), "person");
}

TEST(SemanticKittiTruth, ReadsLabelsAndWritesThemBack) {
  TempFolder dir("semkitti");
  const std::vector<std::uint32_t> raw{0, 9, 40, 252u | (3u << 16), 254u | (3u << 16), 251};
  io::writeSemanticKittiLabels(dir.file("000000.label"), raw);
  io::writeSemanticKittiLabels(dir.file("000001.label"), {9, 9});
  EXPECT_EQ(io::readSemanticKittiLabels(dir.file("000000.label")), raw);
  EXPECT_FALSE(fs::exists(dir.file("000000.label.partial")));

  auto truth = eval::openPointTruth(dir.path.string(), "");
  const core::PointCloud six = cloud(std::vector<Eigen::Vector3d>(6, Eigen::Vector3d(1, 2, 3)));
  const eval::SweepTruth t = truth->truthOf(0, six);
  EXPECT_EQ(t.label,
            (std::vector<PointLabel>{PointLabel::Unknown, PointLabel::Static, PointLabel::Static,
                                     PointLabel::Moving, PointLabel::Moving, PointLabel::Moving}));
  // Instance 3 of the cars and instance 3 of the persons are two objects.
  EXPECT_NE(t.object[3], t.object[4]);
  EXPECT_EQ(truth->className(t.object[3]), "car");
  EXPECT_EQ(truth->className(t.object[4]), "person");
  // Back to SemanticKITTI: unknown 0, static 9, the moving classes with their instance.
  const std::vector<std::uint32_t> back = eval::toSemanticKitti(t, *truth);
  EXPECT_EQ(back[0], 0u);
  EXPECT_EQ(back[1], 9u);
  EXPECT_EQ(back[3] & 0xFFFFu, 252u);
  EXPECT_EQ(back[4] & 0xFFFFu, 254u);

  EXPECT_THROW(truth->truthOf(1, six), eval::EvaluationError);  // 2 labels for 6 points
  EXPECT_THROW(truth->truthOf(2, six), eval::EvaluationError);  // no third file
  { std::ofstream(dir.file("000002.label"), std::ios::binary) << "abc"; }
  EXPECT_THROW(io::readSemanticKittiLabels(dir.file("000002.label")), io::FormatError);
}
