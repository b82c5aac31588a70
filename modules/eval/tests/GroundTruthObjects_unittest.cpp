// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/ObjectRecall.h>
#include <dynobj/eval/SequenceMetrics.h>
#include <dynobj/testing/ScratchPath.h>
#include <gtest/gtest.h>

#include <fstream>

using namespace dynobj;
using namespace dynobj::eval;

namespace {

std::string writeTemp(const std::string& text) {
  const std::string p = dynobj::testing::scratchPath(".csv");
  std::ofstream(p) << text;
  return p;
}

const char* kHeader = "sweep,timestamp_ns,id,class,x,y,z,vx,vy,speed,moving,points\n";

}  // namespace

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
