// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/MovementAnalyzer.h"

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "dynobj/core/Config.h"

namespace dynobj::core {

void MovementParams::visit(ParamVisitor& v) {
  v.value("window", window, {2, 1000});
  v.value("min_window", min_window, {2, 1000});  // >= window: off
  v.value("stop_window", stop_window);
  v.value("stop_speed", stop_speed);
  v.value("min_displacement", min_displacement, kPositive);
  v.value("min_straightness", min_straightness, {0, 1});
  v.value("planar", planar);
  v.degrees("long_object_angle", long_object_angle, {0, M_PI / 2});
  v.value("upright_length", upright_length, {0, 100});
  v.value("upright_height", upright_height, {0, 100});
  v.value("upright_max_elongation", upright_max_elongation, {1, 1e6});
  v.value("rigid_tolerance", rigid_tolerance, {0, 10});
  v.value("rigid_ends_length", rigid_ends_length, {0, 1000});
  v.value("long_object_ego_ratio", long_object_ego_ratio, {0, 1000});
  v.value("max_speed", max_speed, kPositive);
}

void MovementParams::validate() const {
  StageParams::validate();
  requireInRange("stop_window", stop_window, 2, 1000);  // > window: off
  requireInRange("stop_speed", stop_speed, 0, 100);
}

MovementAnalyzer::MovementAnalyzer(const MovementParams& p) : p_(p) {
  p_.validate();
}

bool MovementAnalyzer::rigidMotion(const WindowEntry& a, const WindowEntry& b,
                                   const Eigen::Isometry3d& T_ab, const Eigen::Vector3d& v,
                                   double displacement, bool by_ends) const {
  // Departure from the paper: Eq. (23) alone rejects every elongated object moving along its
  // axis, cars included. A wall sliding into view has one end fixed (its real end, or an
  // occluding edge) while the other follows the view; a car's two ends both move as its
  // centroid does. Ends are compared along the motion direction v, in the window's first frame.
  if (p_.rigid_tolerance <= 0) return false;
  if ((a.end_b - a.end_a).norm() < 1e-6 || (b.end_b - b.end_a).norm() < 1e-6)
    return false;  // ends unknown: no exemption
  const auto along = [&](const Eigen::Vector3d& p) {
    return p.head<2>().dot(v.head<2>().normalized());
  };
  double a0 = along(a.end_a), a1 = along(a.end_b), b0 = along(T_ab * b.end_a),
         b1 = along(T_ab * b.end_b);
  if (a0 > a1) std::swap(a0, a1);
  if (b0 > b1) std::swap(b0, b1);
  const auto movedBy = [&](double travel) {
    const double tol = p_.rigid_tolerance * travel;
    return std::abs((b0 - a0) - travel) <= tol && std::abs((b1 - a1) - travel) <= tol;
  };
  if (movedBy(displacement)) return true;
  const double length = p_.rigid_ends_length;
  if (!by_ends || length <= 0) return false;
  // Beyond the paper (rigid_ends_length): a car passing close by shows its densest points abreast
  // of the sensor, so its centroid lags its ends (`parking` OS0-64 seed 6: ends 1.34 and 1.37 m,
  // centroid 0.54 m), while a wall sliding into view has one end fixed. A short cluster's ends
  // are noise, and an object at rest is no car passing (a walker merging with it shifts its ends).
  const double ends = 0.5 * ((b0 - a0) + (b1 - a1));
  return a1 - a0 >= length && b1 - b0 >= length && ends > displacement && movedBy(ends);
}

MovementDecision MovementAnalyzer::analyse(const Window& window, const FrameChain& chain,
                                           const Cluster& cluster, double dt, bool at_rest) const {
  MovementDecision d;
  // The last k observations; beyond the paper, a younger track is judged on the ones it has
  // (at least min_window) with the same epsilon_d, so only a faster object passes early.
  const auto k = std::min(window.size(), static_cast<std::size_t>(p_.window));
  if (k < static_cast<std::size_t>(std::min(p_.min_window, p_.window))) return d;
  d.early = k < static_cast<std::size_t>(p_.window);
  const long first = window[window.size() - k].frame, last = window.back().frame;
  if (!chain.contains(first) || !chain.reliable(first, last)) return d;
  d.enough_history = true;

  // Eq. (16)-(18): every centroid of the window in the window's first frame, c^{w j} = T^w_j c^j.
  std::vector<Eigen::Vector3d> cw;
  cw.reserve(k);
  for (std::size_t j = window.size() - k; j < window.size(); j++)
    cw.push_back(chain.between(first, window[j].frame) * window[j].centroid);
  if (p_.planar)
    for (Eigen::Vector3d& c : cw) c.z() = 0;

  const Eigen::Isometry3d T_first_last = chain.between(first, last);  // current -> first
  d.displacement = (cw.back() - cw.front()).norm();                   // Eq. (19)
  for (std::size_t j = 1; j < cw.size(); j++) d.path += (cw[j] - cw[j - 1]).norm();  // Eq. (20)
  const double duration = std::max(1e-6, static_cast<double>(last - first) * dt);
  d.speed = d.displacement / duration;
  d.velocity = T_first_last.linear().transpose() * (cw.back() - cw.front()) / duration;
  d.candidate = d.displacement > p_.min_displacement && d.speed <= p_.max_speed;
  // Beyond the paper: the window lags a stop by up to k frames; its last few observations do not.
  const auto m = static_cast<std::size_t>(p_.stop_window);
  if (p_.stop_speed > 0 && k >= m) {
    const long from = window[window.size() - m].frame;
    const double recent = std::max(1e-6, static_cast<double>(last - from) * dt);
    d.stopped = (cw.back() - cw[k - m]).norm() / recent < p_.stop_speed;
  }
  const double straightness = d.early ? std::sqrt(p_.min_straightness) : p_.min_straightness;
  d.drift = d.path <= 0 || d.displacement / d.path < straightness;

  // Eq. (21)-(23), for a cluster with a horizontal spread (without one, all its points in one
  // column, the PCA axis is noise: Clusterer gives it an elongation below 1). A rigid mover is
  // exempt once free space proves it, and so is an upright one shorter than a two-wheeler.
  if (d.candidate && cluster.elongation >= 1.0) {
    const Eigen::Vector3d v = (cw.back() - cw.front()) / d.displacement;  // Eq. (21)
    const Eigen::Matrix3d R = T_first_last.linear();                      // current -> first frame
    const Eigen::Vector3d V =
        R * Eigen::Vector3d(cluster.main_direction.x(), cluster.main_direction.y(), 0);
    const Eigen::Vector2d vh = v.head<2>(), Vh = V.head<2>();
    if (vh.norm() > 1e-9 && Vh.norm() > 1e-9) {
      d.angle =
          std::acos(std::min(1.0, std::abs(vh.normalized().dot(Vh.normalized()))));  // Eq. (23)
      d.rigid = rigidMotion(window[window.size() - k], window.back(), T_first_last, v,
                            d.displacement, !at_rest);
      // Beyond the paper: only where the viewpoint moved enough to make a static wall slide by f.
      const double ego = T_first_last.translation().norm();
      const bool viewpoint_moved =
          p_.long_object_ego_ratio <= 0 || ego * p_.long_object_ego_ratio >= d.displacement;
      const bool upright = p_.upright_length > 0 && cluster.length <= p_.upright_length &&
                           cluster.max.z() - cluster.min.z() >= p_.upright_height &&
                           cluster.elongation <= p_.upright_max_elongation;
      const bool along = d.angle < p_.long_object_angle && viewpoint_moved && !upright;
      d.long_object = along && !d.rigid;
      d.slides = along && d.rigid;
    }
  }
  return d;
}

}  // namespace dynobj::core
