// SPDX-License-Identifier: BSD-3-Clause
// The point-by-point evaluation of real recordings against the pixel evaluation of simulated ones:
// on the committed sample, whose pixels are its points, both must count the same.
#include <dynobj/eval/ExperimentRunner.h>
#include <dynobj/eval/PointEvaluation.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/mrptio/RawlogFrameSource.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

using namespace dynobj;

namespace {

const std::string kSample = std::string(DYNOBJ_SOURCE_DIR) + "/rawlogs/hall-small";

/// The sample's pixel ground truth as per-point truth (a point per valid pixel, in pixel order):
/// what a user's SemanticKITTI labels of such a recording would say.
class PixelTruth final : public eval::PointTruthSource {
 public:
  explicit PixelTruth(const std::string& labels) : file_(io::LabelFile::read(labels)) {}
  eval::SweepTruth truthOf(std::size_t k, const core::PointCloud& pts) const override {
    (void)pts;
    const auto& dyn = file_.sweeps.at(k).pixels;
    eval::SweepTruth t;
    for (std::uint32_t px : *valid_[k]) {
      const bool moving = std::binary_search(dyn.begin(), dyn.end(), px);
      t.label.push_back(moving ? eval::PointLabel::Moving : eval::PointLabel::Static);
      t.object.push_back(moving ? 1 : -1);
    }
    return t;
  }
  std::string className(int) const override { return "person"; }
  std::string describe() const override { return "pixels"; }
  std::vector<const std::vector<std::uint32_t>*> valid_;

 private:
  io::LabelFile file_;
};

/// Valid pixels of every sweep of the sample, in order (the points evaluatePoints makes).
std::vector<std::vector<std::uint32_t>> validPixels() {
  mrptio::RawlogFrameSource src(kSample + "/hall-small.rawlog", mrptio::ObservationConverter(),
                                {"LIDAR"});
  std::vector<std::vector<std::uint32_t>> out;
  mrptio::Frame f;
  while (src.next(f)) out.push_back(io::pixelsOfMask(f.frame.valid));
  return out;
}

}  // namespace

TEST(PointEvaluation, CountsWhatThePixelEvaluationCountsOnTheSample) {
  const auto valid = validPixels();
  PixelTruth truth(kSample + "/hall-small.gt.labels");
  for (const auto& v : valid) truth.valid_.push_back(&v);
  mrptio::RawlogFrameSource src(kSample + "/hall-small.rawlog", mrptio::ObservationConverter(),
                                {"LIDAR"});
  eval::PointEvalOptions po;
  const eval::PointEvaluation e = eval::evaluatePoints(src, truth, po);
  ASSERT_EQ(e.runs.size(), 2u);
  EXPECT_EQ(e.sweeps, valid.size());

  // The same detector over the same frames, scored pixel by pixel: offline (hindsight, the
  // default lag) and online (lag 0).
  const eval::SequenceFiles seq = eval::SequenceFiles::locate(kSample);
  eval::RunOptions ro;
  ro.sensor_label = "LIDAR";
  const eval::RunResult offline = eval::runExperiment(seq, ro);
  ro.params.hindsight.lag = 0;
  const eval::RunResult online = eval::runExperiment(seq, ro);
  for (const auto& [run, pixels] : {std::pair{&e.runs[0], &online}, {&e.runs[1], &offline}}) {
    SCOPED_TRACE(run->mode);
    EXPECT_GT(pixels->metrics.total.tp, 0);
    EXPECT_EQ(run->metrics.total.tp, pixels->metrics.total.tp);
    EXPECT_EQ(run->metrics.total.fp, pixels->metrics.total.fp);
    EXPECT_EQ(run->metrics.total.fn, pixels->metrics.total.fn);
    EXPECT_EQ(run->metrics.total.tn, pixels->metrics.total.tn);
  }
  // Hindsight finds more of the walkers than the causal run.
  EXPECT_GT(e.runs[1].metrics.total.tp, e.runs[0].metrics.total.tp);
}

TEST(PointEvaluation, UnknownModesAreRefused) {
  EXPECT_EQ(eval::parsePointModes("offline"), std::vector<std::string>{"offline"});
  EXPECT_THROW(eval::parsePointModes("online,hindsight"), std::invalid_argument);
  EXPECT_THROW(eval::parsePointModes(""), std::invalid_argument);
}
