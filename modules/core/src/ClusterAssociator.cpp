// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/ClusterAssociator.h"

#include "dynobj/core/Config.h"
#include "dynobj/core/Hungarian.h"

namespace dynobj::core {

void AssociationParams::visit(ParamVisitor& v) {
  v.value("gate_distance", gate_distance);
}

void AssociationParams::validate() const { requirePositive("gate_distance", gate_distance); }

ClusterAssociator::ClusterAssociator(const AssociationParams& p) : p_(p) { p_.validate(); }

Eigen::MatrixXd ClusterAssociator::costMatrix(const std::vector<Eigen::Vector3d>& current,
                                              const std::vector<Eigen::Vector3d>& predicted) const {
  const auto M = static_cast<Eigen::Index>(current.size());
  const auto N = static_cast<Eigen::Index>(predicted.size());
  const double dmax = p_.gate_distance;
  Eigen::MatrixXd D(M + N, N + M);
  D.topRightCorner(M, M).setConstant(2 * dmax);     // current cluster -> dummy: a new object
  D.bottomLeftCorner(N, N).setConstant(2 * dmax);   // dummy -> track: the track is not seen
  D.bottomRightCorner(N, M).setZero();              // dummy -> dummy
  for (Eigen::Index m = 0; m < M; m++)
    for (Eigen::Index n = 0; n < N; n++) {
      const double d = (current[static_cast<std::size_t>(m)] - predicted[static_cast<std::size_t>(n)]).norm();
      D(m, n) = d <= dmax ? d : forbidden();  // Eq. (9)
    }
  return D;
}

std::vector<int> ClusterAssociator::associate(const std::vector<Eigen::Vector3d>& current,
                                              const std::vector<Eigen::Vector3d>& predicted) const {
  std::vector<int> out(current.size(), -1);
  if (current.empty() || predicted.empty()) return out;
  // Pairs beyond d_max are forbidden (Eq. 9), so the assignment splits into independent
  // problems, one per connected component of the "within d_max" graph. Solving each one with its
  // own dummies (Eq. 10-13) gives exactly the optimum of the whole matrix, at a fraction of the
  // O(n^3) cost of one large matrix.
  const std::size_t M = current.size(), N = predicted.size();
  std::vector<std::size_t> parent(M + N);
  for (std::size_t i = 0; i < parent.size(); i++) parent[i] = i;
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  const double d2max = p_.gate_distance * p_.gate_distance;
  for (std::size_t m = 0; m < M; m++)
    for (std::size_t n = 0; n < N; n++)
      if ((current[m] - predicted[n]).squaredNorm() <= d2max) parent[find(m)] = find(M + n);
  std::vector<std::vector<std::size_t>> rows(M + N), cols(M + N);
  for (std::size_t m = 0; m < M; m++) rows[find(m)].push_back(m);
  for (std::size_t n = 0; n < N; n++) cols[find(M + n)].push_back(n);
  std::vector<Eigen::Vector3d> cur, pred;
  for (std::size_t root = 0; root < M + N; root++) {
    if (rows[root].empty() || cols[root].empty()) continue;
    cur.clear();
    pred.clear();
    for (std::size_t m : rows[root]) cur.push_back(current[m]);
    for (std::size_t n : cols[root]) pred.push_back(predicted[n]);
    const std::vector<int> a = solveAssignment(costMatrix(cur, pred));  // Eq. (10)-(13)
    for (std::size_t i = 0; i < cur.size(); i++)
      if (a[i] >= 0 && a[i] < static_cast<int>(pred.size()) &&
          (cur[i] - pred[static_cast<std::size_t>(a[i])]).norm() <= p_.gate_distance)
        out[rows[root][i]] = static_cast<int>(cols[root][static_cast<std::size_t>(a[i])]);
  }
  return out;
}

}  // namespace dynobj::core
