// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/DriftModel.h>
#include <dynobj/eval/ObjectRecall.h>
#include <dynobj/eval/Report.h>
#include <dynobj/eval/SequenceMetrics.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>
#include <mrpt/system/filesystem.h>

#include <fstream>

using namespace dynobj;
using namespace dynobj::eval;

namespace {

std::string writeTemp(const std::string& text) {
  const std::string p = dynobj::testing::scratchPath(".csv");
  std::ofstream(p) << text;
  return p;
}

io::LabelSweep instances(std::int64_t t, std::vector<std::uint32_t> px,
                         std::vector<std::int32_t> ids) {
  io::LabelSweep s;
  s.timestamp_ns = t;
  s.pixels = std::move(px);
  s.ids = std::move(ids);
  return s;
}

const char* kHeader = "sweep,timestamp_ns,id,class,x,y,z,vx,vy,speed,moving,points\n";

}  // namespace

TEST(ObjectRecall, HalfTheObjectsPointsFlaggedCountsAsDetected) {
  GroundTruthObjects::Sweep objects;
  objects.timestamp_ns = 5;
  objects.moving = {{1, "pedestrian"}, {2, "car"}};  // object 3 stands still
  ObjectRecall recall(/*min_points=*/2, /*min_flagged=*/0.5);
  // Object 1: pixels 0-3, two flagged (50 %: detected). Object 2: pixels 10-12, one flagged
  // (33 %: missed). Object 3 (static): ignored. Object 1 again is the only one of a 1-pixel
  // sweep: below min_points, not counted.
  recall.add(instances(5, {0, 1, 2, 3, 10, 11, 12, 20}, {1, 1, 1, 1, 2, 2, 2, 3}), {2, 3, 12, 20},
             objects);
  EXPECT_EQ(recall.total().present, 2);
  EXPECT_EQ(recall.total().detected, 1);
  EXPECT_DOUBLE_EQ(*recall.total().recall(), 0.5);
  EXPECT_EQ(recall.byClass().at("pedestrian").detected, 1);
  EXPECT_EQ(recall.byClass().at("car").detected, 0);
  objects.timestamp_ns = 6;
  recall.add(instances(6, {7}, {1}), {7}, objects);
  EXPECT_EQ(recall.total().present, 2);
  objects.timestamp_ns = 8;
  EXPECT_THROW(recall.add(instances(7, {}, {}), {}, objects), EvaluationError);
}

TEST(ObjectRecall, NoObjectMeansUndefinedNotZero) {
  EXPECT_FALSE(ObjectRecall().total().recall().has_value());
}

TEST(GroundTruthObjects, ReadsMovingObjectsAndNamesBadLines) {
  const auto g = GroundTruthObjects::read(writeTemp(std::string(kHeader) +
                                                    "0,100,0,pedestrian,1,2,0.9,1,0,1,1,30\n"
                                                    "0,100,1,car,5,2,0.9,0,0,0,0,80\n"
                                                    "1,200,0,pedestrian,1.1,2,0.9,1,0,1,1,28\n"));
  ASSERT_EQ(g.sweeps.size(), 2u);
  EXPECT_EQ(g.sweeps[0].moving.size(), 1u);
  EXPECT_EQ(g.sweeps[0].moving.at(0), "pedestrian");
  EXPECT_EQ(g.sweeps[1].timestamp_ns, 200);
  try {
    GroundTruthObjects::read(writeTemp(std::string(kHeader) + "0,100,0,pedestrian,1,2\n"));
    FAIL();
  } catch (const EvaluationError& e) {
    EXPECT_NE(std::string(e.what()).find(":2: expected 12 fields, found 6"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(GroundTruthObjects::read(writeTemp("id,x\n")), EvaluationError);
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

TEST(Report, MarkdownTablePrintsUndefinedAsNa) {
  RunResult r;
  r.sequence = "empty";
  r.description = "nothing dynamic";
  r.metrics.add(1, {}, {}, 10);  // no dynamic point anywhere: precision, recall, IoU, F1 undefined
  const std::string t = markdownTable({r});
  EXPECT_NE(t.find("| empty | nothing dynamic | n/a | n/a | n/a | n/a | n/a | 0.000 % | — |"),
            std::string::npos)
      << t;
}

TEST(DriftModel, ParsesKeysAndRejectsUnknownOnes) {
  const DriftParams p =
      DriftParams::parse("sigma_xy=0,sigma_yaw_deg=0,bias_scale=0.1,bias_yaw_deg=1");
  DriftModel model(p);
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.translation() = Eigen::Vector3d(1, 0, 0);
  const Eigen::Isometry3d c = model.corrupt(m);  // no noise: scale and yaw bias only
  EXPECT_NEAR(c.translation().x(), 1.1, 1e-12);
  EXPECT_NEAR(std::atan2(c.linear()(1, 0), c.linear()(0, 0)), M_PI / 180.0, 1e-12);
  EXPECT_THROW(DriftParams::parse("bias=1"), std::invalid_argument);
  EXPECT_THROW(DriftParams::parse("sigma_xy=abc"), std::invalid_argument);
  EXPECT_THROW(DriftParams::parse("sigma_xy"), std::invalid_argument);
}
