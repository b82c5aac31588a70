// SPDX-License-Identifier: BSD-3-Clause
// Optimal assignment (Kuhn-Munkres / Hungarian method, O(n^2 m)) for a rectangular cost matrix:
// the paper's Eq. (10)-(13). Generic: knows nothing of clusters or dummies (see Tracker).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace dynobj::core {

/// Minimises the summed cost of assigning rows to distinct columns. Every row is assigned when
/// rows <= cols; otherwise every column is. Returns, for each row, its column or -1.
/// Costs must be finite (use a large value for "forbidden").
std::vector<int> solveAssignment(const Eigen::MatrixXd& cost);

/// Total cost of an assignment returned by solveAssignment.
double assignmentCost(const Eigen::MatrixXd& cost, const std::vector<int>& row_to_col);

}  // namespace dynobj::core
