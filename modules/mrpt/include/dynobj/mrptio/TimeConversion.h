// SPDX-License-Identifier: BSD-3-Clause
// MRPT timestamps (100 ns ticks since 1601-01-01) <-> the core's nanoseconds since the Unix epoch.
#pragma once

#include <mrpt/core/Clock.h>

#include <cstdint>

namespace dynobj::mrptio {

/// 100 ns ticks between 1601-01-01 and 1970-01-01 (MRPT's Clock epoch vs Unix).
constexpr std::int64_t kUnixEpochTicks = INT64_C(116444736000000000);

/// Nanoseconds since the Unix epoch; an invalid (default) MRPT timestamp gives 0.
inline std::int64_t toUnixNs(mrpt::Clock::time_point t) {
  if (t == mrpt::Clock::time_point()) return 0;
  return (static_cast<std::int64_t>(t.time_since_epoch().count()) - kUnixEpochTicks) * 100;
}

/// Inverse of toUnixNs (100 ns resolution: the sub-tick part is truncated).
inline mrpt::Clock::time_point fromUnixNs(std::int64_t ns) {
  return mrpt::Clock::time_point(mrpt::Clock::duration(ns / 100 + kUnixEpochTicks));
}

}  // namespace dynobj::mrptio
