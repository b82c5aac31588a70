// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mrptio/TimeConversion.h>
#include <gtest/gtest.h>

using namespace dynobj::mrptio;

TEST(TimeConversion, MatchesMrptSecondsAndRoundTrips) {
  const auto t = mrpt::Clock::fromDouble(1519650000.25);  // 2018-02-26, as in the VLP-16 sample
  EXPECT_EQ(toUnixNs(t), INT64_C(1519650000250000000));
  EXPECT_EQ(fromUnixNs(toUnixNs(t)), t);
  EXPECT_EQ(toUnixNs(mrpt::Clock::time_point()), 0);
  EXPECT_DOUBLE_EQ(mrpt::Clock::toDouble(fromUnixNs(INT64_C(1700000000123456700))),
                   1700000000.1234567);
}
