// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/TrackManager.h"

#include <algorithm>

#include "dynobj/core/Config.h"

namespace dynobj::core {

void TrackingParams::visit(ParamVisitor& v) {
  v.value("prediction", prediction);
  v.value("max_missed", max_missed, {0, 1000});
  v.value("process_noise", process_noise, kPositive);
  v.value("measurement_noise", measurement_noise, kPositive);
  v.value("hysteresis", hysteresis);
  v.value("confirm_frames", confirm_frames, {1, 1000});
  v.value("release_frames", release_frames, {1, 1000});
  v.value("settled_frames", settled_frames, {1, 100000});
  v.value("stop_at_rest", stop_at_rest);
}

TrackManager::TrackManager(const TrackingParams& p, int window)
    : p_(p), window_(static_cast<std::size_t>(std::max(window, 2))) {
  p_.validate();
}

void TrackManager::reset() {
  tracks_.clear();
  next_id_ = 0;
}

void TrackManager::predict(const Eigen::Isometry3d& motion, double dt) {
  const Eigen::Isometry3d to_cur = motion.inverse();  // T_{cur<-prev}
  const Eigen::Matrix2d R = to_cur.linear().topLeftCorner<2, 2>();
  Eigen::Matrix4d J = Eigen::Matrix4d::Zero();
  J.topLeftCorner<2, 2>() = R;
  J.bottomRightCorner<2, 2>() = R;
  Eigen::Matrix4d F = Eigen::Matrix4d::Identity();
  F(0, 2) = F(1, 3) = dt;
  const double q = p_.process_noise * p_.process_noise;
  Eigen::Matrix4d Q = Eigen::Matrix4d::Zero();  // white acceleration
  Q(0, 0) = Q(1, 1) = q * dt * dt * dt * dt / 4;
  Q(0, 2) = Q(2, 0) = Q(1, 3) = Q(3, 1) = q * dt * dt * dt / 2;
  Q(2, 2) = Q(3, 3) = q * dt * dt;
  for (Track& t : tracks_) {
    const Eigen::Vector3d p = to_cur * t.position();  // Eq. (8): the previous centroid, seen now
    t.state.head<2>() = p.head<2>();
    t.z = p.z();
    t.state.tail<2>() = R * t.state.tail<2>();
    t.cov = J * t.cov * J.transpose();
    if (p_.prediction) {
      t.state = F * t.state;
      t.cov = F * t.cov * F.transpose() + Q;
    }
    t.cluster = -1;
  }
}

std::vector<Eigen::Vector3d> TrackManager::predicted() const {
  std::vector<Eigen::Vector3d> out;
  out.reserve(tracks_.size());
  for (const Track& t : tracks_) out.push_back(t.position());
  return out;
}

std::vector<double> TrackManager::gates(const ClusterAssociator& a, double dt) const {
  std::vector<double> out;
  out.reserve(tracks_.size());
  for (const Track& t : tracks_) {
    const WindowEntry& seen = t.window.back();
    out.push_back(t.window.size() < 2
                      ? a.gate((t.missed + 1) * dt, (seen.end_b - seen.end_a).norm())
                      : a.gate(0, 0));
  }
  return out;
}

std::vector<char> TrackManager::movers() const {
  std::vector<char> out;
  out.reserve(tracks_.size());
  for (const Track& t : tracks_) out.push_back(t.dynamic && t.missed == 0);
  return out;
}

void TrackManager::update(long frame, const std::vector<Cluster>& clusters,
                          const std::vector<int>& cluster_to_track) {
  const double r = p_.measurement_noise * p_.measurement_noise;
  std::vector<char> seen(tracks_.size(), 0);
  for (std::size_t m = 0; m < clusters.size(); m++) {
    const Eigen::Vector3d& c = clusters[m].centroid;
    if (cluster_to_track[m] < 0) {  // a new object
      Track t;
      t.id = next_id_++;
      t.state << c.x(), c.y(), 0, 0;
      t.cov = Eigen::Vector4d(r, r, 4.0, 4.0).asDiagonal();
      t.z = c.z();
      t.radius = 0.5 * (clusters[m].max - clusters[m].min).head<2>().norm();
      t.cluster = static_cast<int>(m);
      t.window.reserve(window_ + 1);
      t.window.emplace_back(frame, c, clusters[m].end_a, clusters[m].end_b);
      tracks_.push_back(std::move(t));
      seen.push_back(1);
      continue;
    }
    const auto idx = static_cast<std::size_t>(cluster_to_track[m]);
    Track& t = tracks_[idx];
    seen[idx] = 1;
    t.cluster = static_cast<int>(m);
    t.missed = 0;
    t.z = c.z();
    t.radius = 0.5 * (clusters[m].max - clusters[m].min).head<2>().norm();
    // Kalman update with the centroid (x, y).
    Eigen::Matrix<double, 2, 4> Hm = Eigen::Matrix<double, 2, 4>::Zero();
    Hm(0, 0) = Hm(1, 1) = 1;
    const Eigen::Matrix2d S = Hm * t.cov * Hm.transpose() + Eigen::Matrix2d::Identity() * r;
    const Eigen::Matrix<double, 4, 2> K = t.cov * Hm.transpose() * S.inverse();
    t.state += K * (c.head<2>() - t.state.head<2>());
    t.cov = (Eigen::Matrix4d::Identity() - K * Hm) * t.cov;
    if (!p_.prediction) t.state.head<2>() = c.head<2>();  // the paper: no filtering
    t.window.emplace_back(frame, c, clusters[m].end_a, clusters[m].end_b);
    if (t.window.size() > window_)
      t.window.erase(t.window.begin(),
                     t.window.begin() + static_cast<std::ptrdiff_t>(t.window.size() - window_));
  }
  const int max_missed = p_.prediction ? p_.max_missed : 0;
  std::vector<Track> kept;
  kept.reserve(tracks_.size());
  for (std::size_t i = 0; i < tracks_.size(); i++) {
    Track& t = tracks_[i];
    t.age++;
    if (!seen[i] && ++t.missed > max_missed) continue;
    kept.push_back(std::move(t));
  }
  tracks_ = std::move(kept);
}

void TrackManager::decide(Track& t, const MovementDecision& d) {
  t.decision = d;
  const bool moving = d.moving();
  if (!p_.hysteresis) {
    t.dynamic = moving;
    return;
  }
  // A clear stop, or a space that was clearly occupied already: released at once, hysteresis
  // would lag it.
  if ((d.stopped || d.refuted) && t.dynamic) {
    t.dynamic = false;
    t.halted = p_.stop_at_rest && d.stopped;
    t.positives = 0;
    t.negatives = p_.release_frames;
  } else if (moving) {
    t.positives++;
    t.negatives = 0;
    if (t.positives >= p_.confirm_frames) {
      t.dynamic = true;
      t.settled = false;
      t.halted = false;
    }
  } else if (d.enough_history && !d.early) {  // a short window proves no standstill
    t.negatives++;
    t.positives = 0;
    if (t.negatives >= p_.release_frames) t.dynamic = false;
    if (t.negatives >= p_.settled_frames) t.settled = true;
  }
}

}  // namespace dynobj::core
