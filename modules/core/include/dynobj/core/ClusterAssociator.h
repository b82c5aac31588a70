// SPDX-License-Identifier: BSD-3-Clause
// Paper III-B-3, Eq. (8)-(13): Global Nearest Neighbour association of the current clusters with
// the tracks, by the Hungarian method on a cost matrix extended with dummy targets.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "dynobj/core/Params.h"

namespace dynobj::core {

struct AssociationParams : public StageParams {
  double gate_distance = 1.0;  ///< d_max [m]: farther pairs cost "infinity" (Eq. 9)

  void visit(ParamVisitor& v) override;
  void validate() const override;
};

class ClusterAssociator {
 public:
  explicit ClusterAssociator(const AssociationParams& p = {});

  /// The (M+N) x (N+M) matrix of Eq. (10): rows = M current clusters then N dummies, columns =
  /// N predicted tracks then M dummies. Real pairs cost their distance (Eq. 8) or `forbidden`
  /// beyond d_max (Eq. 9); a real row or column paired with a dummy costs 2 d_max; dummy-dummy 0.
  Eigen::MatrixXd costMatrix(const std::vector<Eigen::Vector3d>& current,
                             const std::vector<Eigen::Vector3d>& predicted) const;

  /// For each current cluster, the index of its track in `predicted`, or -1 (a new object).
  std::vector<int> associate(const std::vector<Eigen::Vector3d>& current,
                             const std::vector<Eigen::Vector3d>& predicted) const;

  double forbidden() const { return 1e6 * p_.gate_distance; }

 private:
  AssociationParams p_;
};

}  // namespace dynobj::core
