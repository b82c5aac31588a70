// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/io/LabelFile.h>
#include <dynobj/label/LabelEditor.h>
#include <dynobj/mrptio/RawlogFrameSource.h>
#include <dynobj/mrptio/RawlogIndex.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>

#include "../../core/tests/SyntheticScene.h"

using namespace dynobj;
using dynobj::test::Post;
using dynobj::test::Scene;

namespace {

constexpr std::int64_t kT0 = 1700000000000000000;
constexpr std::int64_t kDt = 100000000;  // 10 Hz

/// Pixels whose point lies on the post at (px, py) with radius `rad`; without `base`, not its
/// last 4 cm (which the ground segmenter takes for floor).
std::vector<std::uint32_t> postPixels(const core::LidarFrame& f, double px, double py,
                                      double rad = 0.3, bool base = false) {
  std::vector<std::uint32_t> out;
  for (int r = 0; r < f.rows(); r++)
    for (int c = 0; c < f.cols(); c++) {
      if (!f.isValid(r, c)) continue;
      const cv::Vec3f& p = f.xyz(r, c);
      if (std::abs(std::hypot(p[0] - px, p[1] - py) - rad) < 1e-3 && (base || p[2] > -0.96f))
        out.push_back(static_cast<std::uint32_t>(r * f.cols() + c));
    }
  return out;
}

/// Renders the scene with the sensor at `sensor_x` and the post(s) as given; the pixels of the
/// first post in `truth` (in the sensor frame: post position minus the sensor's).
core::LidarFrame frameWith(std::vector<Post> posts, double sensor_x, std::int64_t stamp,
                           int cols = 360) {
  Scene scene;
  scene.posts = std::move(posts);
  scene.sensor.translation() = Eigen::Vector3d(sensor_x, 0, 0);
  return test::render(scene, test::smallSensor(16, cols), true, stamp);
}

/// "+p" for pixels only in `got`, "-p" for pixels only in `want` (row,col): a readable failure.
std::string diff(const std::vector<std::uint32_t>& got, const std::vector<std::uint32_t>& want,
                 int W = 360) {
  std::string out;
  std::set<std::uint32_t> g(got.begin(), got.end()), w(want.begin(), want.end());
  for (auto p : g)
    if (!w.count(p)) out += " +" + std::to_string(p / W) + "," + std::to_string(p % W);
  for (auto p : w)
    if (!g.count(p)) out += " -" + std::to_string(p / W) + "," + std::to_string(p % W);
  return out;
}

Eigen::Isometry3d at(double x) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(x, 0, 0);
  return T;
}

std::string tempDir(const std::string& name) {
  const auto d = std::filesystem::temp_directory_path() / ("dynobj_label_" + name);
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d.string();
}

/// The session's parameters without the feet rule: growing exactly as the detector grows.
label::LabelParams noFeet() {
  label::LabelParams p;
  p.feet = false;
  return p;
}

}  // namespace

TEST(LabelEditor, GrowFromAClickGivesExactlyTheObjectsPixels) {
  label::MemorySweeps src;
  src.add(frameWith({{4, 0, 0.3, 1.8}, {4, 1.2, 0.3, 1.8}}, 0, kT0));
  label::LabelEditor s(src, noFeet());
  const auto f = s.sweep(0);
  const auto truth = postPixels(f->frame, 4, 0);
  ASSERT_GT(truth.size(), 10u);
  const std::uint32_t click = truth[truth.size() / 2];
  const auto grown = s.grow(0, static_cast<int>(click) / f->frame.cols(),
                            static_cast<int>(click) % f->frame.cols());
  EXPECT_EQ(grown, truth) << diff(grown, truth);
}

TEST(LabelEditor, DistanceThresholdSeparatesOrJoinsCloseObjects) {
  label::MemorySweeps src;  // post b stands behind post a's left edge: adjacent in the image,
  src.add(frameWith({{4, 0, 0.3, 1.8}, {4.5, 0.5, 0.3, 1.8}}, 0, kT0));  // ~0.3 m apart in 3D
  label::LabelEditor s(src, noFeet());
  const auto f = s.sweep(0);
  const auto a = postPixels(f->frame, 4, 0), b = postPixels(f->frame, 4.5, 0.5);
  const int W = f->frame.cols();
  const std::uint32_t click = a[a.size() / 2];
  // At 4 m, epsilon = distance + 1.2 x 4 m x 1 deg = distance + 0.084 m.
  EXPECT_EQ(s.grow(0, static_cast<int>(click) / W, static_cast<int>(click) % W, -1, 0.05), a);
  std::vector<std::uint32_t> both(a);
  both.insert(both.end(), b.begin(), b.end());
  std::sort(both.begin(), both.end());
  EXPECT_EQ(s.grow(0, static_cast<int>(click) / W, static_cast<int>(click) % W, -1, 0.4), both);
}

TEST(LabelEditor, GrowingNeverEntersGroundOrAnotherObject) {
  label::MemorySweeps src;
  src.add(frameWith({{4, 0, 0.3, 1.8}, {4, 0.85, 0.3, 1.8}}, 0, kT0));
  label::LabelEditor s(src, noFeet());
  const auto f = s.sweep(0);
  const int W = f->frame.cols();
  const auto a = postPixels(f->frame, 4, 0), b = postPixels(f->frame, 4, 0.85);
  s.setObject(0, 7, b);  // post b is labelled already: growing from a stays on a
  EXPECT_EQ(s.grow(0, static_cast<int>(a[0]) / W, static_cast<int>(a[0]) % W), a);
  int floor_px = -1;  // a floor pixel far from the posts
  for (int c = 0; c < W && floor_px < 0; c++)
    if (f->frame.isValid(15, c) && f->ground(15, c) && std::abs(f->frame.xyz(15, c)[1]) > 2)
      floor_px = 15 * W + c;
  ASSERT_GE(floor_px, 0);
  try {
    s.grow(0, floor_px / W, floor_px % W);
    FAIL() << "grew from the floor";
  } catch (const label::LabelError& e) {
    EXPECT_NE(std::string(e.what()).find("ground"), std::string::npos) << e.what();
  }
  EXPECT_THROW(s.grow(0, 16, 0), label::LabelError);  // outside the image
  EXPECT_THROW(s.grow(3, 0, 0), label::LabelError);   // no such sweep
}

TEST(LabelEditor, SetObjectTakesPixelsFromOtherObjectsAndTracksReview) {
  label::MemorySweeps src;
  src.add(frameWith({{4, 0, 0.3, 1.8}}, 0, kT0));
  label::LabelEditor s(src, noFeet());
  s.setObject(0, 1, {5, 6, 7});
  s.setObject(0, 2, {7, 8}, label::LabelState::proposed);
  ASSERT_NE(s.object(0, 1), nullptr);
  EXPECT_EQ(s.object(0, 1)->pixels, (std::vector<std::uint32_t>{5, 6}));
  EXPECT_EQ(s.object(0, 2)->pixels, (std::vector<std::uint32_t>{7, 8}));
  EXPECT_FALSE(s.labels(0).reviewed);
  s.setReviewed(0, true);
  EXPECT_EQ(s.object(0, 2)->state, label::LabelState::confirmed);
  EXPECT_EQ(s.reviewedCount(), 1u);
  s.setObject(0, 1, {});  // erase
  EXPECT_EQ(s.object(0, 1), nullptr);
  EXPECT_THROW(s.setObject(0, 3, {16u * 360u}), label::LabelError);
  EXPECT_THROW(s.setObject(0, 0, {1}), label::LabelError);
}

TEST(LabelEditor, PropagationFollowsAWalkerWithOdometryAndVelocity) {
  // The sensor drives +x at 2 m/s, the walker walks +y at 1.5 m/s (0.15 m per sweep).
  label::MemorySweeps src;
  for (int k = 0; k < 4; k++)
    src.add(frameWith({{6, 0.15 * k, 0.3, 1.8}, {6, -2.5, 0.3, 1.8}}, 0.2 * k, kT0 + k * kDt),
            at(0.2 * k));
  label::LabelEditor s(src, noFeet());
  const int W = s.cols();
  const auto truth0 = postPixels(s.sweep(0)->frame, 6, 0);
  const auto grown = s.grow(0, static_cast<int>(truth0[0]) / W, static_cast<int>(truth0[0]) % W);
  ASSERT_EQ(grown, truth0);
  const int id = s.newObject("pedestrian");
  s.setObject(0, id, grown);
  for (int k = 0; k < 3; k++) {
    const label::Propagation p = s.propagate(static_cast<std::size_t>(k), id);
    SCOPED_TRACE(k);
    ASSERT_TRUE(p.found);
    EXPECT_EQ(p.ego_motion, "odometry");
    const auto& f = s.sweep(static_cast<std::size_t>(k + 1))->frame;
    const auto truth = postPixels(f, 6 - 0.2 * (k + 1), 0.15 * (k + 1));
    ASSERT_NE(s.object(static_cast<std::size_t>(k + 1), id), nullptr);
    EXPECT_EQ(s.object(static_cast<std::size_t>(k + 1), id)->pixels, truth)
        << diff(s.object(static_cast<std::size_t>(k + 1), id)->pixels, truth);
    EXPECT_EQ(s.object(static_cast<std::size_t>(k + 1), id)->state, label::LabelState::proposed);
    EXPECT_FALSE(s.labels(static_cast<std::size_t>(k + 1)).reviewed);
    if (k > 0) {  // the velocity comes from the previous sweep's label (the visible surface's
                  // centroid, which shifts a little as the view turns)
      EXPECT_NEAR(p.velocity.y(), 1.5, 0.3);
      EXPECT_NEAR(p.velocity.x(), 0.0, 0.3);
    }
  }
  // A confirmed label in the next sweep is kept as it is.
  s.setObject(2, id, {1, 2, 3});
  const auto kept = s.propagate(1, id);
  EXPECT_TRUE(kept.kept);
  EXPECT_EQ(s.object(2, id)->pixels, (std::vector<std::uint32_t>{1, 2, 3}));
}

TEST(LabelEditor, PropagationReportsALostObject) {
  label::MemorySweeps src;
  src.add(frameWith({{6, 0, 0.3, 1.8}}, 0, kT0), at(0));
  src.add(frameWith({}, 0, kT0 + kDt), at(0));  // the walker is gone
  label::LabelEditor s(src, noFeet());
  s.setObject(0, 1, postPixels(s.sweep(0)->frame, 6, 0));
  const auto p = s.propagate(0, 1);
  EXPECT_FALSE(p.found);
  EXPECT_EQ(s.object(1, 1), nullptr);
  EXPECT_THROW(s.propagate(1, 1), label::LabelError);  // last sweep
  EXPECT_THROW(s.propagate(0, 9), label::LabelError);  // unknown object
}

TEST(LabelEditor, SaveWritesLabelsInstancesAndReviewAndResumes) {
  label::MemorySweeps src;
  for (int k = 0; k < 3; k++)
    src.add(frameWith({{6, 0.15 * k, 0.3, 1.8}}, 0, kT0 + k * kDt), at(0));
  const std::string dir = tempDir("save");
  const std::string base = dir + "/walk";
  std::vector<std::uint32_t> px0;
  {
    label::LabelEditor s(src, noFeet());
    px0 = postPixels(s.sweep(0)->frame, 6, 0);
    const int walker = s.newObject("pedestrian", true);
    const int parked = s.newObject("car", false);
    s.setObject(0, walker, px0);
    s.setObject(0, parked, {0, 1});
    s.setReviewed(0, true);
    ASSERT_TRUE(s.propagate(0, walker).found);  // sweep 1: a proposal, unreviewed
    s.save(base, "walk.rawlog");
  }
  for (const auto& f : label::LabelEditor::outputFiles(base))
    EXPECT_TRUE(std::filesystem::exists(f)) << f;
  EXPECT_FALSE(std::filesystem::exists(base + ".labels.partial"));

  const io::LabelFile dyn = io::LabelFile::read(base + ".labels");
  ASSERT_EQ(dyn.sweeps.size(), 3u);
  EXPECT_TRUE(dyn.has_review);
  EXPECT_EQ(dyn.reviewed, (std::vector<std::uint8_t>{1, 0, 0}));
  EXPECT_EQ(dyn.sweeps[0].pixels, px0);  // the parked car is not moving: not in the label file
  EXPECT_EQ(dyn.sweeps[0].timestamp_ns, kT0);
  EXPECT_EQ(dyn.unreviewedSweeps(), (std::vector<std::size_t>{1, 2}));
  try {
    dyn.requireReviewed(base + ".labels");
    FAIL();
  } catch (const io::LabelFileError& e) {
    EXPECT_NE(std::string(e.what()).find("2 of 3 sweeps were not reviewed"), std::string::npos)
        << e.what();
  }
  const io::LabelFile inst = io::LabelFile::read(base + ".instances");
  EXPECT_TRUE(inst.instances);
  EXPECT_EQ(inst.sweeps[0].pixels.size(), px0.size() + 2);
  EXPECT_EQ(inst.sweeps[0].pixels[0], 0u);
  EXPECT_EQ(inst.sweeps[0].ids[0], 2);

  label::LabelEditor r(src, {});
  r.load(base);
  EXPECT_EQ(r.reviewedCount(), 1u);
  ASSERT_NE(r.object(0, 1), nullptr);
  EXPECT_EQ(r.object(0, 1)->pixels, px0);
  EXPECT_EQ(r.object(0, 1)->state, label::LabelState::confirmed);
  ASSERT_NE(r.object(1, 1), nullptr);
  EXPECT_EQ(r.object(1, 1)->state, label::LabelState::proposed);
  EXPECT_EQ(r.objects().at(2).cls, "car");
  EXPECT_FALSE(r.objects().at(2).moving);
  EXPECT_EQ(r.newObject(), 3);  // ids continue after the saved ones
}

TEST(LabelEditor, ResumingLabelsOfAnotherSensorOrRecordingIsRefused) {
  label::MemorySweeps src;
  src.add(frameWith({}, 0, kT0));
  src.add(frameWith({}, 0, kT0 + kDt));
  const std::string base = tempDir("other") + "/x";
  label::LabelEditor(src, {}).save(base);

  label::MemorySweeps narrow;  // another sensor mode: 180 columns
  narrow.add(frameWith({}, 0, kT0, 180));
  narrow.add(frameWith({}, 0, kT0 + kDt, 180));
  label::LabelEditor s(narrow, {});
  try {
    s.load(base);
    FAIL();
  } catch (const label::LabelError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("16x360"), std::string::npos) << m;
    EXPECT_NE(m.find("16x180"), std::string::npos) << m;
  }
  EXPECT_THROW(s.loadPrelabels(base + ".labels"), label::LabelError);

  label::MemorySweeps later;  // the same sensor, other times
  later.add(frameWith({}, 0, kT0 + 5 * kDt));
  later.add(frameWith({}, 0, kT0 + 6 * kDt));
  label::LabelEditor l(later, {});
  EXPECT_THROW(l.load(base), label::LabelError);
  EXPECT_THROW(l.load(base + "-missing"), label::LabelError);
}

TEST(LabelEditor, AFailedSaveKeepsEverythingAndLeavesNoFile) {
  label::MemorySweeps src;
  src.add(frameWith({{6, 0, 0.3, 1.8}}, 0, kT0));
  label::LabelEditor s(src, noFeet());
  s.setObject(0, 1, {3, 4});
  const std::string dir = tempDir("unwritable");
  { std::ofstream(dir + "/file") << "x"; }
  const std::string bad = dir + "/file/labels";  // a file where a folder should be
  EXPECT_THROW(s.save(bad), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(bad + ".labels"));
  EXPECT_EQ(s.object(0, 1)->pixels, (std::vector<std::uint32_t>{3, 4}));
  s.save(dir + "/ok");
  EXPECT_EQ(io::LabelFile::read(dir + "/ok.instances").sweeps[0].pixels,
            (std::vector<std::uint32_t>{3, 4}));
}

TEST(LabelEditor, DetectorOutputBecomesPrelabelsPerConnectedGroup) {
  label::MemorySweeps src;
  src.add(frameWith({}, 0, kT0));
  src.add(frameWith({}, 0, kT0 + kDt));
  const std::string dir = tempDir("pre");
  {
    io::LabelFileWriter w(dir + "/det.labels", 16, 360);
    w.write(kT0, {0, 1, 100, 361});  // two groups: {0, 1, 361} and {100}
    w.write(kT0 + kDt, {});
    w.close();
  }
  label::LabelEditor s(src, noFeet());
  EXPECT_EQ(s.loadPrelabels(dir + "/det.labels"), 2u);
  ASSERT_EQ(s.labels(0).objects.size(), 2u);
  EXPECT_EQ(s.labels(0).objects[0].pixels, (std::vector<std::uint32_t>{0, 1, 361}));
  EXPECT_EQ(s.labels(0).objects[0].state, label::LabelState::prelabel);
  EXPECT_EQ(s.labels(0).objects[1].pixels, (std::vector<std::uint32_t>{100}));
  EXPECT_FALSE(s.labels(0).reviewed);
}

TEST(RawlogSweeps, ReadsTheSampleInAnyOrderLikeTheSequentialReader) {
  const std::string sample = std::string(DYNOBJ_SOURCE_DIR) + "/rawlogs/hall-small/hall-small";
  label::RawlogSweeps sweeps(sample + ".rawlog", mrptio::ObservationConverter(), "");
  ASSERT_EQ(sweeps.size(), 40u);
  EXPECT_EQ(sweeps.sensorLabel(), "LIDAR");
  const io::LabelFile truth = io::LabelFile::read(sample + ".gt.labels");
  for (std::size_t k = 0; k < 40; k++) EXPECT_EQ(sweeps.timestamp(k), truth.sweeps[k].timestamp_ns);
  // Sequential frames as every other tool reads them.
  mrptio::RawlogFrameSource seq(sample + ".rawlog", mrptio::ObservationConverter(), {});
  std::vector<core::LidarFrame> frames;
  mrptio::Frame f;
  while (seq.next(f)) {  // deep copies: the source reuses its buffers
    core::LidarFrame c;
    c.timestamp_ns = f.frame.timestamp_ns;
    c.range = f.frame.range.clone();
    c.intensity = f.frame.intensity.clone();
    frames.push_back(c);
  }
  ASSERT_EQ(frames.size(), 40u);
  for (std::size_t k : {39u, 0u, 17u, 18u, 3u}) {  // backwards and forwards in a gzip file
    core::LidarFrame got;
    std::optional<Eigen::Isometry3d> pose;
    sweeps.load(k, got, pose);
    SCOPED_TRACE(k);
    EXPECT_EQ(got.timestamp_ns, frames[k].timestamp_ns);
    EXPECT_EQ(cv::norm(got.range, frames[k].range, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(got.intensity, frames[k].intensity, cv::NORM_INF), 0.0);
    EXPECT_TRUE(pose.has_value());  // the sample has odometry
  }
  // The same through the index directly: gzip with a decompressor state every 1 MB (the sample
  // is 22 MB uncompressed), and the rawlog decompressed (plain seeks).
  const std::string plain = tempDir("plain") + "/s.rawlog";
  ASSERT_EQ(std::system(("gzip -dc '" + sample + ".rawlog' > '" + plain + "'").c_str()), 0);
  for (const std::string& file : {sample + ".rawlog", plain}) {
    mrptio::RawlogIndex index(file, mrptio::ObservationConverter(), {"", {}, 1u << 20});
    if (file == plain)
      EXPECT_EQ(index.checkpoints(), 0u);
    else
      EXPECT_TRUE(index.checkpoints() > 10 && index.checkpoints() <= 22) << index.checkpoints();
    for (std::size_t k : {39u, 0u, 38u, 1u, 25u, 24u, 26u}) {
      mrptio::Frame got;
      index.read(k, got);
      SCOPED_TRACE(file + " sweep " + std::to_string(k));
      EXPECT_EQ(got.frame.timestamp_ns, frames[k].timestamp_ns);
      EXPECT_EQ(cv::norm(got.frame.range, frames[k].range, cv::NORM_INF), 0.0);
    }
  }
  EXPECT_THROW(label::RawlogSweeps(sample + ".missing", mrptio::ObservationConverter(), ""),
               mrptio::RawlogError);
  EXPECT_THROW(label::RawlogSweeps(sample + ".rawlog", mrptio::ObservationConverter(), "OTHER"),
               mrptio::RawlogError);
}

TEST(LabelEditor, TheFeetRuleAddsTheBaseBelowTheObjectOnly) {
  label::MemorySweeps src;
  src.add(frameWith({{4, 0, 0.3, 1.8}}, 0, kT0));
  label::LabelEditor with(src, {});  // feet on (the default)
  label::LabelEditor without(src, noFeet());
  const auto& f = with.sweep(0)->frame;
  const int W = f.cols();
  const auto body = postPixels(f, 4, 0), all = postPixels(f, 4, 0, 0.3, true);
  ASSERT_GT(all.size(), body.size());  // the post's base is ground for the segmenter
  const std::uint32_t click = body[body.size() / 2];
  const auto a = without.grow(0, static_cast<int>(click) / W, static_cast<int>(click) % W);
  EXPECT_EQ(a, body) << diff(a, body);
  const auto b = with.grow(0, static_cast<int>(click) / W, static_cast<int>(click) % W);
  std::set<std::uint32_t> grown(b.begin(), b.end());
  for (std::uint32_t p : all) EXPECT_TRUE(grown.count(p)) << "base pixel " << p / W << "," << p % W;
  // Anything else is a ground pixel right below a pixel of the grown object (the floor where it
  // meets the post, which a 2-degree beam cannot tell from the post's base).
  const auto ground = with.sweep(0)->ground;
  for (std::uint32_t p : b) {
    if (std::binary_search(all.begin(), all.end(), p)) continue;
    const int r = static_cast<int>(p) / W, c = static_cast<int>(p) % W;
    EXPECT_TRUE(ground(r, c) && r > 0 && grown.count(static_cast<std::uint32_t>((r - 1) * W + c)))
        << r << "," << c;
  }
}
