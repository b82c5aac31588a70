// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/MovementAnalyzer.h"

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

#include "dynobj/core/Config.h"

namespace dynobj::core {

void MovementParams::visit(ParamVisitor& v) {
  v.value("window", window);
  v.value("min_displacement", min_displacement);
  v.value("min_straightness", min_straightness);
  v.degrees("long_object_angle", long_object_angle);
  v.value("long_object_elongation", long_object_elongation);
  v.value("long_object_length", long_object_length);
  v.value("max_speed", max_speed);
}

void MovementParams::validate() const {
  requireInRange("window", window, 2, 1000);
  requirePositive("min_displacement", min_displacement);
  requireInRange("min_straightness", min_straightness, 0, 1);
  requireInRange("long_object_angle", long_object_angle, 0, M_PI / 2);
  requireInRange("long_object_elongation", long_object_elongation, 1, 1000);
  requireInRange("long_object_length", long_object_length, 0, 1000);
  requirePositive("max_speed", max_speed);
}

MovementAnalyzer::MovementAnalyzer(const MovementParams& p) : p_(p) { p_.validate(); }

MovementDecision MovementAnalyzer::analyse(const Window& window,
                                           const FrameChain& chain, const Cluster& cluster,
                                           double dt) const {
  MovementDecision d;
  const auto k = static_cast<std::size_t>(p_.window);
  if (window.size() < k) return d;
  const long first = window[window.size() - k].first, last = window.back().first;
  if (!chain.contains(first) || !chain.reliable(first, last)) return d;
  d.enough_history = true;

  // Eq. (16)-(18): every centroid of the window in the window's first frame, c^{w j} = T^w_j c^j.
  std::vector<Eigen::Vector3d> cw;
  cw.reserve(k);
  for (std::size_t j = window.size() - k; j < window.size(); j++)
    cw.push_back(chain.between(first, window[j].first) * window[j].second);

  d.displacement = (cw.back() - cw.front()).norm();                   // Eq. (19)
  for (std::size_t j = 1; j < cw.size(); j++) d.path += (cw[j] - cw[j - 1]).norm();  // Eq. (20)
  d.speed = d.displacement / std::max(1e-6, static_cast<double>(last - first) * dt);
  d.candidate = d.displacement > p_.min_displacement && d.speed <= p_.max_speed;
  d.drift = d.path <= 0 || d.displacement / d.path < p_.min_straightness;

  // Eq. (21)-(23), for elongated clusters only (a compact cluster's PCA axis is meaningless).
  if (d.candidate && cluster.elongation >= p_.long_object_elongation &&
      cluster.length >= p_.long_object_length) {
    const Eigen::Vector3d v = (cw.back() - cw.front()) / d.displacement;  // Eq. (21)
    const Eigen::Matrix3d R = chain.between(first, last).linear();       // current -> first frame
    const Eigen::Vector3d V = R * Eigen::Vector3d(cluster.main_direction.x(), cluster.main_direction.y(), 0);
    const Eigen::Vector2d vh = v.head<2>(), Vh = V.head<2>();
    if (vh.norm() > 1e-9 && Vh.norm() > 1e-9) {
      d.angle = std::acos(std::min(1.0, std::abs(vh.normalized().dot(Vh.normalized()))));  // Eq. (23)
      d.long_object = d.angle < p_.long_object_angle;
    }
  }
  return d;
}

}  // namespace dynobj::core
