// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/DriftModel.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace dynobj;
using namespace dynobj::eval;

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
