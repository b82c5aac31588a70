// SPDX-License-Identifier: BSD-3-Clause
// SequenceRunner: per-sensor detectors, the one-sensor rule, external motion from TUM poses per
// sensor, ground truth matched by timestamp (and the errors naming what does not match).
#include <dynobj/mrptio/SequenceRunner.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace dm = dynobj::mrptio;
using dynobj::core::LidarFrame;
using dynobj::core::SensorModel;

namespace {

/// `n` frames of an 8 x 32 sensor (a ring of returns at 5 m), 0.1 s apart from t = 1 s, labels
/// alternating between `labels`.
class FakeFrames : public dm::FrameSource {
 public:
  FakeFrames(int n, std::vector<std::string> labels) : n_(n), labels_(std::move(labels)) {}
  bool next(dm::Frame& f) override {
    if (k_ >= n_) return false;
    SensorModel s;
    s.rows = 8;
    s.cols = 32;
    f.frame = LidarFrame(s);
    // Ranges differ from sweep to sweep: an exact repeat is a duplicate sweep (core::FrameCheck).
    const float r = 5.f + 0.01f * static_cast<float>(k_);
    for (int c = 0; c < 32; c++) f.frame.setPixel(4, c, r, 100.f, cv::Vec3f(r, 0.f, 0.f), c);
    f.frame.timestamp_ns = 1000000000 + 100000000LL * k_;
    f.index = static_cast<std::size_t>(k_);
    f.sensor_label = labels_[static_cast<std::size_t>(k_) % labels_.size()];
    k_++;
    return true;
  }
  void rewind() override { k_ = 0; }
  std::string describe() const override { return "fake"; }
  int produced() const { return k_; }

 private:
  int n_, k_ = 0;
  std::vector<std::string> labels_;
};

std::string write(const std::string& name, const std::string& text) {
  const std::string p = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(p) << text;
  return p;
}

void expectThrowWith(const std::function<void()>& f, const std::string& what) {
  try {
    f();
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(SequenceRunner, OneDetectorPerSensorLabelAndTheOneSensorRule) {
  FakeFrames src(4, {"A", "B"});
  dm::SequenceRunner runner(src, {});
  std::vector<std::string> seen;
  EXPECT_EQ(runner.run([&](const dm::FrameResult& r) {
    ASSERT_NE(r.detection, nullptr);
    EXPECT_EQ(r.truth, nullptr);
    seen.push_back(r.frame.sensor_label);
  }),
            4u);
  EXPECT_EQ(seen, (std::vector<std::string>{"A", "B", "A", "B"}));
  EXPECT_EQ(runner.detectors().sensors(), 2u);

  FakeFrames two(4, {"A", "B"});
  dm::SequenceOptions one;
  one.single_sensor = true;
  expectThrowWith([&] { dm::SequenceRunner(two, one).run([](const dm::FrameResult&) {}); },
                  "fake holds several LiDARs ('A', 'B'): choose one with --sensor-label");
  FakeFrames none(0, {"A"});
  expectThrowWith([&] { dm::SequenceRunner(none, {}).run([](const dm::FrameResult&) {}); },
                  "no LiDAR observation in fake");
}

TEST(SequenceRunner, HindsightHoldsEachSensorsFramesForTheLagAndKeepsTheirOrder) {
  // 10 Hz frames, lag 1 s: the first callback comes once a sensor's 11th frame is detected; every
  // frame still gets exactly one callback, in the source's order, the last ones at the end.
  FakeFrames src(30, {"A", "B"});
  dm::SequenceRunner runner(src, {});
  std::vector<int> produced_at;
  std::vector<std::size_t> order;
  EXPECT_EQ(runner.run([&](const dm::FrameResult& r) {
    ASSERT_NE(r.detection, nullptr);
    EXPECT_EQ(r.detection->timestamp_ns, r.frame.frame.timestamp_ns);
    produced_at.push_back(src.produced());
    order.push_back(r.frame.index);
  }),
            30u);
  ASSERT_EQ(order.size(), 30u);
  for (std::size_t i = 0; i < order.size(); i++) EXPECT_EQ(order[i], i);
  EXPECT_EQ(produced_at.front(), 21);  // frame 20 is A's 11th
  EXPECT_EQ(produced_at.back(), 30);

  FakeFrames online_src(5, {"A"});
  dm::SequenceOptions online;
  online.detector.hindsight.lag = 0;  // the paper's online behaviour: no frame is held
  std::vector<int> at;
  dm::SequenceRunner(online_src, online).run([&](const dm::FrameResult& r) {
    at.push_back(online_src.produced());
    EXPECT_EQ(static_cast<int>(r.frame.index) + 1, online_src.produced());
  });
  EXPECT_EQ(at, (std::vector<int>{1, 2, 3, 4, 5}));
}

TEST(SequenceRunner, StepReadsOneFrameAndHandsOnWhatTheLagReleases) {
  // run() is the loop over step(): stepped by hand, the same frames come in the same order, each
  // callback during the step that released it; the end releases the held frames, and stays the end.
  FakeFrames ran_src(15, {"A"});
  std::vector<std::size_t> ran;
  dm::SequenceRunner(ran_src, {}).run([&](const dm::FrameResult& r) {
    ran.push_back(r.frame.index);
  });

  FakeFrames src(15, {"A"});
  dm::SequenceRunner runner(src, {});
  std::vector<std::size_t> stepped;
  std::vector<std::size_t> per_step;
  const auto collect = [&](const dm::FrameResult& r) {
    ASSERT_NE(r.detection, nullptr);
    EXPECT_EQ(r.detection->timestamp_ns, r.frame.frame.timestamp_ns);
    stepped.push_back(r.frame.index);
  };
  for (int k = 0; k < 15; k++) {
    const std::size_t before = stepped.size();
    ASSERT_TRUE(runner.step(collect));
    EXPECT_EQ(runner.frames(), static_cast<std::size_t>(k + 1));
    per_step.push_back(stepped.size() - before);
  }
  // 10 Hz, lag 1 s: nothing for the first 10 frames, then one frame per step.
  EXPECT_EQ(per_step, (std::vector<std::size_t>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1}));
  EXPECT_FALSE(runner.step(collect));  // the end: the 10 held frames
  EXPECT_EQ(stepped.size(), 15u);
  EXPECT_EQ(stepped, ran);
  EXPECT_FALSE(runner.step(collect));
  EXPECT_EQ(stepped.size(), 15u);
  EXPECT_EQ(src.produced(), 15);

  FakeFrames none(0, {"A"});  // no frame: not an error for step() (run() throws)
  dm::SequenceRunner empty(none, {});
  EXPECT_FALSE(empty.step(collect));
  EXPECT_EQ(empty.frames(), 0u);
}

TEST(SequenceRunner, PosesGiveEachSensorTheMotionSinceItsOwnPreviousFrame) {
  const std::string tum = write("dynobj_runner.tum",
                                "1.0 0 0 0 0 0 0 1\n1.1 1 0 0 0 0 0 1\n"
                                "1.2 3 0 0 0 0 0 1\n1.3 6 0 0 0 0 0 1\n");
  FakeFrames src(4, {"A", "B"});
  dm::SequenceOptions o;
  o.poses = tum;
  std::vector<std::optional<double>> dx;
  dm::SequenceRunner(src, o).run([&](const dm::FrameResult& r) {
    ASSERT_NE(r.pose, nullptr);
    dx.push_back(r.motion ? std::optional<double>(r.motion->translation().x()) : std::nullopt);
  });
  ASSERT_EQ(dx.size(), 4u);
  EXPECT_FALSE(dx[0]);
  EXPECT_FALSE(dx[1]);
  EXPECT_DOUBLE_EQ(*dx[2], 3.0);  // A: pose at 1.2 s seen from its pose at 1.0 s
  EXPECT_DOUBLE_EQ(*dx[3], 5.0);  // B: 1.3 s from 1.1 s

  FakeFrames more(5, {"A"});  // no pose at 1.4 s
  expectThrowWith([&] { dm::SequenceRunner(more, o).run([](const dm::FrameResult&) {}); },
                  "has no pose at 1400000000 ns (frame 4)");
}

TEST(SequenceRunner, GroundTruthIsMatchedByTimestamp) {
  const std::string gt = write("dynobj_runner.labels",
                               "# dynobj-labels v1 rows=8 cols=32\n1000000000 1 130\n"
                               "1100000000 0\n");
  FakeFrames src(2, {"A"});
  dm::SequenceOptions o;
  o.ground_truth = gt;
  std::size_t dynamic = 0;
  dm::SequenceRunner(src, o).run([&](const dm::FrameResult& r) {
    ASSERT_NE(r.truth, nullptr);
    EXPECT_EQ(r.truth_index, r.frame.index);
    dynamic += static_cast<std::size_t>(cv::countNonZero(r.truthMask()));
  });
  EXPECT_EQ(dynamic, 1u);
  FakeFrames longer(3, {"A"});
  expectThrowWith(
      [&] { dm::SequenceRunner(longer, o).run([](const dm::FrameResult&) {}); },
      "ground truth has no sweep at 1200000000 ns (frame 2): the timestamps do not match");
  const std::string small =
      write("dynobj_runner_small.labels", "# dynobj-labels v1 rows=4 cols=32\n1000000000 0\n");
  FakeFrames again(1, {"A"});
  o.ground_truth = small;
  expectThrowWith([&] { dm::SequenceRunner(again, o).run([](const dm::FrameResult&) {}); },
                  "ground truth is 4x32 but the scans are 8x32 (frame 0 at 1000000000 ns)");
}

// A label file used as a classification (dynobj-mapclean --labels): unreviewed sweeps accepted,
// messages name it as a label file; as ground truth the same file is refused.
TEST(GroundTruth, LabelFileRoleAcceptsUnreviewedSweepsAndNamesItself) {
  const std::string f = write("dynobj_runner_review.labels",
                              "# dynobj-labels v1 rows=8 cols=32\n# reviewed 0\n1000000000 1 130\n"
                              "1100000000 2 3 4\n");
  expectThrowWith([&] { (void)dm::GroundTruth{f}; }, "1 of 2 sweeps were not reviewed");
  const dm::GroundTruth labels(f, {"label file", false});
  FakeFrames src(3, {"A"});
  dm::Frame fr;
  std::size_t k = 9;
  ASSERT_TRUE(src.next(fr));
  EXPECT_EQ(labels.sweep(fr.frame, fr.index, &k).pixels, (std::vector<std::uint32_t>{130}));
  EXPECT_EQ(k, 0u);
  ASSERT_TRUE(src.next(fr));
  EXPECT_EQ(labels.sweep(fr.frame, fr.index, &k).pixels, (std::vector<std::uint32_t>{3, 4}));
  EXPECT_EQ(k, 1u);
  EXPECT_FALSE(labels.labels().isReviewed(1));
  ASSERT_TRUE(src.next(fr));
  expectThrowWith([&] { labels.sweep(fr.frame, fr.index); },
                  "dynobj_runner_review.labels': label file has no sweep at 1200000000 ns (frame "
                  "2): the timestamps do not match");
}
