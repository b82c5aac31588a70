// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/SequenceMetrics.h>
#include <gtest/gtest.h>

using namespace dynobj;
using eval::SequenceMetrics;

namespace {

using Sweeps = std::vector<std::pair<std::int64_t, std::vector<std::uint32_t>>>;

io::LabelFile file(const Sweeps& sweeps, int rows = 4, int cols = 8) {
  io::LabelFile f;
  f.rows = rows;
  f.cols = cols;
  for (const auto& [t, pixels] : sweeps) {
    f.sweeps.emplace_back();
    f.sweeps.back().timestamp_ns = t;
    f.sweeps.back().pixels = pixels;
  }
  return f;
}

std::string errorOf(const io::LabelFile& a, const io::LabelFile& b) {
  try {
    SequenceMetrics::compute(a, b);
  } catch (const eval::EvaluationError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SequenceMetrics, HandComputedCounts) {
  // Sweep 1: truth {1,2,3,4}, predicted {3,4,5}: TP 2, FP 1, FN 2.
  // Sweep 2: truth {}, predicted {7}: TP 0, FP 1, FN 0 (precision 0, recall undefined).
  // Sweep 3: truth {10}, predicted {10}: TP 1.
  const auto m = SequenceMetrics::compute(file({{100, {1, 2, 3, 4}}, {200, {}}, {300, {10}}}),
                                          file({{100, {3, 4, 5}}, {200, {7}}, {300, {10}}}));
  ASSERT_EQ(m.sweeps.size(), 3u);
  EXPECT_EQ(m.sweeps[0].counts.tp, 2);
  EXPECT_EQ(m.sweeps[0].counts.fp, 1);
  EXPECT_EQ(m.sweeps[0].counts.fn, 2);
  EXPECT_FALSE(m.sweeps[1].counts.recall().has_value());
  EXPECT_DOUBLE_EQ(*m.sweeps[1].counts.precision(), 0.0);
  // Micro: TP 3, FP 2, FN 2 -> precision 3/5, recall 3/5, IoU 3/7, F1 6/10.
  EXPECT_EQ(m.total.tp, 3);
  EXPECT_EQ(m.total.fp, 2);
  EXPECT_EQ(m.total.fn, 2);
  EXPECT_DOUBLE_EQ(*m.total.precision(), 0.6);
  EXPECT_DOUBLE_EQ(*m.total.recall(), 0.6);
  EXPECT_DOUBLE_EQ(*m.total.iou(), 3.0 / 7.0);
  EXPECT_DOUBLE_EQ(*m.total.f1(), 0.6);
  // Per-sweep recall is defined on sweeps 1 and 3 only: {0.5, 1.0}.
  const auto d = m.distribution(SequenceMetrics::Metric::Recall);
  EXPECT_EQ(d.sweeps, 2u);
  EXPECT_DOUBLE_EQ(*d.median, 0.75);
  EXPECT_DOUBLE_EQ(*d.q1, 0.625);
  EXPECT_DOUBLE_EQ(*d.q3, 0.875);
}

TEST(SequenceMetrics, NothingDynamicAnywhereIsUndefinedNotZero) {
  const auto m = SequenceMetrics::compute(file({{1, {}}, {2, {}}}), file({{1, {}}, {2, {}}}));
  EXPECT_FALSE(m.total.precision().has_value());
  EXPECT_FALSE(m.total.recall().has_value());
  EXPECT_FALSE(m.total.iou().has_value());
  EXPECT_FALSE(m.total.f1().has_value());
  EXPECT_EQ(eval::formatMetric(m.total.precision()), "n/a");
  EXPECT_EQ(m.distribution(SequenceMetrics::Metric::F1).sweeps, 0u);
  EXPECT_FALSE(m.distribution(SequenceMetrics::Metric::F1).median.has_value());
  EXPECT_EQ(eval::formatMetric(0.8734), "0.873");
}

TEST(SequenceMetrics, MismatchesAreErrorsNamingTheSweep) {
  EXPECT_NE(
      errorOf(file({{1, {}}}), file({{1, {}}}, 4, 16)).find("4x8 but the predictions are 4x16"),
      std::string::npos);
  EXPECT_NE(errorOf(file({{1, {}}, {2, {}}}), file({{1, {}}}))
                .find("ground-truth sweep 1 (line 3, t = 2 ns) has no prediction"),
            std::string::npos);
  EXPECT_NE(errorOf(file({{1, {}}}), file({{1, {}}, {2, {}}})).find("prediction sweep 1"),
            std::string::npos);
  EXPECT_NE(errorOf(file({{1, {}}, {2, {}}}), file({{1, {}}, {3, {}}}))
                .find("sweep 1 (line 3): ground truth at t = 2 ns, prediction at 3 ns"),
            std::string::npos);
}

TEST(SequenceMetrics, StaticPointsFlaggedNeedsEverySweepsPointCount) {
  SequenceMetrics m;
  // 100 valid points, truth {1, 2}, predicted {2, 3, 4}: TP 1, FP 2, FN 1, TN 96.
  m.add(1, {1, 2}, {2, 3, 4}, 100, 4.5);
  EXPECT_EQ(m.total.tn, 96);
  EXPECT_DOUBLE_EQ(*m.staticFlagged(), 2.0 / 98.0);
  EXPECT_DOUBLE_EQ(m.sweeps[0].ms, 4.5);
  m.add(2, {}, {}, -1);  // unknown point count: the static share is no longer known
  EXPECT_FALSE(m.staticFlagged().has_value());
  EXPECT_FALSE(SequenceMetrics().staticFlagged().has_value());
}
