// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/Hungarian.h"

#include <limits>
#include <stdexcept>

namespace dynobj::core {
namespace {

/// Shortest-augmenting-path Hungarian method for n <= m (rows <= cols), 1-based potentials.
std::vector<int> solveRowsLeCols(const Eigen::MatrixXd& a) {
  const int n = static_cast<int>(a.rows()), m = static_cast<int>(a.cols());
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> u(n + 1, 0), v(m + 1, 0);
  std::vector<int> p(m + 1, 0), way(m + 1, 0);  // p[j]: row matched to column j (1-based)
  for (int i = 1; i <= n; i++) {
    p[0] = i;
    int j0 = 0;
    std::vector<double> minv(m + 1, inf);
    std::vector<char> used(m + 1, 0);
    do {
      used[j0] = 1;
      const int i0 = p[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= m; j++) {
        if (used[j]) continue;
        const double cur = a(i0 - 1, j - 1) - u[i0] - v[j];
        if (cur < minv[j]) {
          minv[j] = cur;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= m; j++) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {  // augment along the path
      const int j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> row_to_col(static_cast<std::size_t>(n), -1);
  for (int j = 1; j <= m; j++)
    if (p[j] != 0) row_to_col[static_cast<std::size_t>(p[j] - 1)] = j - 1;
  return row_to_col;
}

}  // namespace

std::vector<int> solveAssignment(const Eigen::MatrixXd& cost) {
  if (!cost.allFinite()) throw std::invalid_argument("solveAssignment: costs must be finite");
  if (cost.rows() == 0 || cost.cols() == 0)
    return std::vector<int>(static_cast<std::size_t>(cost.rows()), -1);
  if (cost.rows() <= cost.cols()) return solveRowsLeCols(cost);
  const std::vector<int> col_to_row = solveRowsLeCols(cost.transpose());
  std::vector<int> row_to_col(static_cast<std::size_t>(cost.rows()), -1);
  for (std::size_t c = 0; c < col_to_row.size(); c++)
    if (col_to_row[c] >= 0)
      row_to_col[static_cast<std::size_t>(col_to_row[c])] = static_cast<int>(c);
  return row_to_col;
}

double assignmentCost(const Eigen::MatrixXd& cost, const std::vector<int>& row_to_col) {
  double total = 0;
  for (std::size_t r = 0; r < row_to_col.size(); r++)
    if (row_to_col[r] >= 0) total += cost(static_cast<Eigen::Index>(r), row_to_col[r]);
  return total;
}

}  // namespace dynobj::core
