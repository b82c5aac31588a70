// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/ObjectRecall.h>
#include <dynobj/eval/SequenceMetrics.h>
#include <gtest/gtest.h>

using namespace dynobj;
using namespace dynobj::eval;

namespace {

io::LabelSweep instances(std::int64_t t, std::vector<std::uint32_t> px,
                         std::vector<std::int32_t> ids) {
  io::LabelSweep s;
  s.timestamp_ns = t;
  s.pixels = std::move(px);
  s.ids = std::move(ids);
  return s;
}

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
