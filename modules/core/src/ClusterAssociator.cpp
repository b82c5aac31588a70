// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/ClusterAssociator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dynobj/core/Config.h"
#include "dynobj/core/Hungarian.h"

namespace dynobj::core {

void AssociationParams::visit(ParamVisitor& v) {
  v.value("gate_distance", gate_distance, kPositive);
  v.value("new_track_speed", new_track_speed, {0, 100});
  v.value("new_track_length", new_track_length, {0, 100});
  v.value("split_radius", split_radius, {0, 10});
  v.value("split_min_share", split_min_share, {0, 0.5});
  v.value("split_match_radius", split_match_radius, {0, 10});
  v.value("split_rest_majority", split_rest_majority);
  v.value("split_hold_back", split_hold_back);
  v.value("movers_first", movers_first);
  v.value("carve_dropped", carve_dropped);
}

ClusterAssociator::ClusterAssociator(const AssociationParams& p) : p_(p) {
  p_.validate();
}

double ClusterAssociator::gate(double unknown_velocity_seconds, double length) const {
  if (length < p_.new_track_length) return p_.gate_distance;
  return p_.gate_distance + p_.new_track_speed * std::max(0.0, unknown_velocity_seconds);
}

Eigen::MatrixXd ClusterAssociator::costMatrix(const std::vector<Eigen::Vector3d>& current,
                                              const std::vector<Eigen::Vector3d>& predicted,
                                              const std::vector<double>& gates) const {
  if (!gates.empty() && gates.size() != predicted.size())
    throw std::invalid_argument("ClusterAssociator: one gate per predicted track");
  const auto M = static_cast<Eigen::Index>(current.size());
  const auto N = static_cast<Eigen::Index>(predicted.size());
  Eigen::MatrixXd D(M + N, N + M);
  const double dmax = p_.gate_distance;
  D.topRightCorner(M, M).setConstant(2 * dmax);    // current cluster -> dummy: a new object
  D.bottomLeftCorner(N, N).setConstant(2 * dmax);  // dummy -> track: the track is not seen
  D.bottomRightCorner(N, M).setZero();             // dummy -> dummy
  for (Eigen::Index n = 0; n < N; n++) {
    const auto j = static_cast<std::size_t>(n);
    const double gate = gates.empty() ? dmax : gates[j];
    for (Eigen::Index m = 0; m < M; m++) {
      const double d = (current[static_cast<std::size_t>(m)] - predicted[j]).norm();
      D(m, n) = d <= gate ? d : forbidden();  // Eq. (9), with this track's gate
    }
  }
  return D;
}

std::vector<int> ClusterAssociator::associate(const std::vector<Eigen::Vector3d>& current,
                                              const std::vector<Eigen::Vector3d>& predicted,
                                              const std::vector<double>& gates) const {
  std::vector<int> out(current.size(), -1);
  if (current.empty() || predicted.empty()) return out;
  if (!gates.empty() && gates.size() != predicted.size())
    throw std::invalid_argument("ClusterAssociator: one gate per predicted track");
  const auto gateOf = [&](std::size_t n) { return gates.empty() ? p_.gate_distance : gates[n]; };
  // Pairs beyond their track's gate are forbidden (Eq. 9), so the assignment splits into
  // independent problems, one per connected component of the "within the gate" graph. Solving each
  // one with its own dummies (Eq. 10-13) gives exactly the optimum of the whole matrix, at a
  // fraction of the O(n^3) cost of one large matrix.
  const std::size_t M = current.size(), N = predicted.size();
  std::vector<std::size_t> parent(M + N);
  for (std::size_t i = 0; i < parent.size(); i++) parent[i] = i;
  auto find = [&](std::size_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  // The edges, through a grid of the predictions: cells of the widest gate in x and y, so that a
  // cluster's tracks within their gates lie in its own cell or the 8 around it (the components,
  // and so the result, are those of testing every pair).
  double widest = 0;
  for (std::size_t n = 0; n < N; n++) widest = std::max(widest, gateOf(n));
  const auto index = [widest](double v) {  // a non-finite coordinate is within no gate: any cell
    const double q = std::floor(v / widest);
    return std::isfinite(q) ? static_cast<long>(std::clamp(q, -1e15, 1e15)) : 0L;
  };
  const auto cellOf = [&](const Eigen::Vector3d& p) {
    return std::pair<long, long>(index(p.x()), index(p.y()));
  };
  std::vector<std::pair<std::pair<long, long>, std::size_t>> cells;
  cells.reserve(N);
  for (std::size_t n = 0; n < N; n++) cells.emplace_back(cellOf(predicted[n]), n);
  std::sort(cells.begin(), cells.end());
  for (std::size_t m = 0; m < M; m++) {
    const auto [cx, cy] = cellOf(current[m]);
    for (long dx = -1; dx <= 1; dx++)
      for (long dy = -1; dy <= 1; dy++) {
        const std::pair<long, long> key(cx + dx, cy + dy);
        auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(key, std::size_t{0}));
        for (; it != cells.end() && it->first == key; ++it) {
          const std::size_t n = it->second;
          if ((current[m] - predicted[n]).squaredNorm() <= gateOf(n) * gateOf(n))
            parent[find(m)] = find(M + n);
        }
      }
  }
  // Group rows and columns by component: (root, index) pairs sorted by root (two allocations,
  // not one per component).
  std::vector<std::pair<std::size_t, std::size_t>> rows, cols;
  rows.reserve(M);
  cols.reserve(N);
  for (std::size_t m = 0; m < M; m++) rows.emplace_back(find(m), m);
  for (std::size_t n = 0; n < N; n++) cols.emplace_back(find(M + n), n);
  std::sort(rows.begin(), rows.end());
  std::sort(cols.begin(), cols.end());
  std::vector<Eigen::Vector3d> cur, pred;
  std::vector<double> gate;
  std::size_t r0 = 0, c0 = 0;
  while (r0 < rows.size()) {
    const std::size_t root = rows[r0].first;
    std::size_t r1 = r0;
    while (r1 < rows.size() && rows[r1].first == root) r1++;
    while (c0 < cols.size() && cols[c0].first < root) c0++;
    std::size_t c1 = c0;
    while (c1 < cols.size() && cols[c1].first == root) c1++;
    if (c1 > c0) {  // clusters with candidate tracks: solve this component (Eq. 10-13)
      cur.clear();
      pred.clear();
      gate.clear();
      for (std::size_t i = r0; i < r1; i++) cur.push_back(current[rows[i].second]);
      for (std::size_t j = c0; j < c1; j++) {
        pred.push_back(predicted[cols[j].second]);
        gate.push_back(gateOf(cols[j].second));
      }
      const std::vector<int> a = solveAssignment(costMatrix(cur, pred, gate));
      for (std::size_t i = 0; i < cur.size(); i++)
        if (a[i] >= 0 && a[i] < static_cast<int>(pred.size()) &&
            (cur[i] - pred[static_cast<std::size_t>(a[i])]).norm() <=
                gate[static_cast<std::size_t>(a[i])])
          out[rows[r0 + i].second] =
              static_cast<int>(cols[c0 + static_cast<std::size_t>(a[i])].second);
    }
    r0 = r1;
    c0 = c1;
  }
  return out;
}

}  // namespace dynobj::core

namespace dynobj::core {

std::vector<int> ClusterAssociator::associateMoversFirst(
    const std::vector<Eigen::Vector3d>& current, const std::vector<Eigen::Vector3d>& predicted,
    const std::vector<double>& gates, const std::vector<char>& first) const {
  if (!p_.movers_first || std::find(first.begin(), first.end(), 1) == first.end())
    return associate(current, predicted, gates);
  if (first.size() != predicted.size() || gates.size() != predicted.size())
    throw std::invalid_argument("ClusterAssociator: one gate and one flag per predicted track");
  // Round 1: the movers, with the clusters whose nearest prediction of all is a mover's, within
  // half its gate (the mover's own cluster, where it was predicted; not an object beside it, which
  // lies nearer its own track, nor one farther off when the mover's own is missing).
  std::vector<Eigen::Vector3d> movers;
  std::vector<double> half_gates;
  std::vector<std::size_t> mover_index;
  for (std::size_t n = 0; n < predicted.size(); n++)
    if (first[n]) {
      movers.push_back(predicted[n]);
      half_gates.push_back(gates[n] / 2);
      mover_index.push_back(n);
    }
  std::vector<Eigen::Vector3d> near;  // the clusters of round 1
  std::vector<std::size_t> near_index;
  for (std::size_t m = 0; m < current.size(); m++) {
    // Only a cluster within half a mover's gate can be one (the few movers first, then all).
    bool candidate = false;
    for (std::size_t k = 0; k < movers.size() && !candidate; k++)
      candidate = (current[m] - movers[k]).squaredNorm() <= half_gates[k] * half_gates[k];
    if (!candidate) continue;
    std::size_t best = 0;
    double best_d2 = std::numeric_limits<double>::infinity();
    for (std::size_t n = 0; n < predicted.size(); n++) {
      const double d2 = (current[m] - predicted[n]).squaredNorm();
      if (d2 < best_d2) best_d2 = d2, best = n;
    }
    if (first[best] && best_d2 <= gates[best] * gates[best] / 4) {
      near.push_back(current[m]);
      near_index.push_back(m);
    }
  }
  std::vector<int> out(current.size(), -1);
  const std::vector<int> first_round = associate(near, movers, half_gates);
  for (std::size_t i = 0; i < first_round.size(); i++)
    if (first_round[i] >= 0) out[near_index[i]] = first_round[i];
  std::vector<char> matched(predicted.size(), 0);
  std::vector<Eigen::Vector3d> left;
  std::vector<std::size_t> left_index;
  for (std::size_t m = 0; m < out.size(); m++) {
    if (out[m] >= 0) {
      const std::size_t n = mover_index[static_cast<std::size_t>(out[m])];
      out[m] = static_cast<int>(n);
      matched[n] = 1;
    } else {
      left.push_back(current[m]);
      left_index.push_back(m);
    }
  }
  // Round 2: every other track (the movers round 1 left too) with the clusters left.
  std::vector<Eigen::Vector3d> rest;
  std::vector<double> rest_gates;
  std::vector<std::size_t> rest_index;
  for (std::size_t n = 0; n < predicted.size(); n++)
    if (!matched[n]) {
      rest.push_back(predicted[n]);
      rest_gates.push_back(gates[n]);
      rest_index.push_back(n);
    }
  const std::vector<int> second = associate(left, rest, rest_gates);
  for (std::size_t i = 0; i < second.size(); i++)
    if (second[i] >= 0)
      out[left_index[i]] = static_cast<int>(rest_index[static_cast<std::size_t>(second[i])]);
  return out;
}

}  // namespace dynobj::core
