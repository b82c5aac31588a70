// SPDX-License-Identifier: BSD-3-Clause
#include <dynobj/core/Hungarian.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <numeric>
#include <random>

using namespace dynobj::core;

namespace {

/// Exhaustive minimum over all injective row->column maps (rows <= cols) or the transpose.
double bruteForce(const Eigen::MatrixXd& c) {
  if (c.rows() > c.cols()) return bruteForce(c.transpose());
  std::vector<int> cols(static_cast<std::size_t>(c.cols()));
  std::iota(cols.begin(), cols.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {  // permutations of columns; the first rows() entries are the assignment
    double s = 0;
    for (int r = 0; r < c.rows(); r++) s += c(r, cols[static_cast<std::size_t>(r)]);
    best = std::min(best, s);
  } while (std::next_permutation(cols.begin(), cols.end()));
  return best;
}

}  // namespace

TEST(Hungarian, HandExample) {
  Eigen::MatrixXd c(3, 3);
  c << 4, 1, 3,  //
      2, 0, 5,   //
      3, 2, 2;
  const auto a = solveAssignment(c);
  EXPECT_EQ(a, (std::vector<int>{1, 0, 2}));  // 1 + 2 + 2 = 5
  EXPECT_DOUBLE_EQ(assignmentCost(c, a), 5.0);
}

TEST(Hungarian, EqualsBruteForceOnRandomMatrices) {
  std::mt19937 rng(1234);
  std::uniform_real_distribution<double> val(0.0, 10.0);
  std::uniform_int_distribution<int> dim(1, 8);
  for (int trial = 0; trial < 300; trial++) {
    const int r = dim(rng), c = dim(rng);
    Eigen::MatrixXd m(r, c);
    for (int i = 0; i < r; i++)
      for (int j = 0; j < c; j++)
        m(i, j) = (trial % 3 == 0) ? std::floor(val(rng)) : val(rng);  // ties too
    const auto a = solveAssignment(m);
    ASSERT_EQ(a.size(), static_cast<std::size_t>(r));
    std::vector<int> seen;
    for (int x : a)
      if (x >= 0) seen.push_back(x);
    std::sort(seen.begin(), seen.end());
    EXPECT_TRUE(std::adjacent_find(seen.begin(), seen.end()) == seen.end()) << "column used twice";
    EXPECT_EQ(seen.size(), static_cast<std::size_t>(std::min(r, c)));
    EXPECT_NEAR(assignmentCost(m, a), bruteForce(m), 1e-9) << "trial " << trial << "\n" << m;
  }
}

TEST(Hungarian, EmptyAndInvalid) {
  EXPECT_TRUE(solveAssignment(Eigen::MatrixXd(0, 3)).empty());
  EXPECT_EQ(solveAssignment(Eigen::MatrixXd(2, 0)), (std::vector<int>{-1, -1}));
  Eigen::MatrixXd bad(1, 1);
  bad << std::numeric_limits<double>::infinity();
  EXPECT_THROW(solveAssignment(bad), std::invalid_argument);
}
