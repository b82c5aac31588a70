// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/mapclean/ScanSource.h>
#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "FrameFixture.h"

namespace mc = dynobj::mapclean;

namespace {

constexpr std::int64_t kSecond = 1000000000;

/// Scans at 0, 1, ..., n-1 s; counts the scans it converted.
class CountingSource final : public mc::ScanSource {
 public:
  explicit CountingSource(int n, int* converted) : n_(n), converted_(converted) {}
  bool next(mc::Scan& s) override {
    if (k_ >= n_) return false;
    s.frame = dynobj::mapclean::test::tinyFrame({}, k_ * kSecond);
    s.index = static_cast<std::size_t>(k_++);
    ++*converted_;
    return true;
  }
  void rewind() override { k_ = 0; }
  std::string describe() const override { return "counting source"; }

 private:
  int n_, k_ = 0;
  int* converted_;
};

std::vector<std::size_t> indices(mc::ScanSource& s) {
  std::vector<std::size_t> out;
  mc::Scan scan;
  while (s.next(scan)) out.push_back(scan.index);
  return out;
}

}  // namespace

TEST(TimeWindowSource, GivesTheScansOfItsWindowWithTheirNumbers) {
  int converted = 0;
  mc::TimeWindowSource w(std::make_unique<CountingSource>(10, &converted), 3 * kSecond - 1,
                         6 * kSecond);
  EXPECT_EQ(indices(w), (std::vector<std::size_t>{3, 4, 5}));
  EXPECT_FALSE(w.reachedEnd());  // stopped at the scan at 6 s, before the input's end
  EXPECT_EQ(converted, 7);       // this source cannot pass over scans: 0-5 and the one at 6 s
  w.rewind();
  EXPECT_EQ(indices(w), (std::vector<std::size_t>{3, 4, 5}));
}

TEST(TimeWindowSource, SaysWhenTheInputEndedInsideTheWindow) {
  int converted = 0;
  mc::TimeWindowSource w(std::make_unique<CountingSource>(10, &converted), 8 * kSecond,
                         20 * kSecond);
  EXPECT_EQ(indices(w), (std::vector<std::size_t>{8, 9}));
  EXPECT_TRUE(w.reachedEnd());
}

TEST(TimeWindowSource, FirstScanTimeRewinds) {
  int converted = 0;
  CountingSource s(3, &converted);
  EXPECT_EQ(mc::firstScanTime(s), 0);
  EXPECT_EQ(indices(s).size(), 3u);
  CountingSource empty(0, &converted);
  EXPECT_THROW(mc::firstScanTime(empty), std::runtime_error);
}
