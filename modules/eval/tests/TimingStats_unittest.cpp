// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/eval/TimingStats.h>
#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

using namespace dynobj::eval;

TEST(TimingStats, MedianAndP99) {
  TimingStats s;
  for (int i = 1; i <= 101; i++) {
    dynobj::core::StageTimings t;
    t.total = i;
    t.clustering = 2 * i;
    s.add(t);
  }
  EXPECT_EQ(s.frames(), 101u);
  EXPECT_DOUBLE_EQ(s.percentile("total", 50), 51);
  EXPECT_DOUBLE_EQ(s.percentile("total", 99), 100);
  EXPECT_DOUBLE_EQ(s.percentile("clustering", 50), 102);
  EXPECT_THROW(s.percentile("nope", 50), std::invalid_argument);
  std::ostringstream out;
  s.print(out);
  EXPECT_NE(out.str().find("total"), std::string::npos);
}
