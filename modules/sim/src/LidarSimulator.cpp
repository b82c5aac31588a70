// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/LidarSimulator.h"

#include <dynobj/core/SphericalProjection.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "PartOps.h"

namespace dynobj::sim {

using detail::intersectPart;
using detail::placed;
using detail::swayed;
using detail::swung;

struct LidarSimulator::Posed {
  Part part;  ///< in world coordinates
  int actor = -1;
  std::uint32_t uid = 0;   ///< index in the posed world (keys the random draws of foliage)
  Eigen::Vector3d center;  ///< bounding sphere
  double radius = 0;
};

namespace {

constexpr int kGroup = 16;  ///< columns sharing one broad-phase list (and one time with distortion)

/// Ouster-like signal vs range: suppressed in the near field (below ~near_range), flat mid-range,
/// falling off far away.
double rangeGain(double r, double near_range) {
  const double q = r / near_range;
  return (1.0 - std::exp(-q * q)) / (1.0 + std::pow(r / 60.0, 4));
}

/// Does the azimuth interval [a - h, a + h] contain the interval [lo, hi] partially?
bool overlaps(double a, double h, double lo, double hi) {
  if (h >= M_PI) return true;
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  const double d = std::abs(std::atan2(std::sin(a - mid), std::cos(a - mid)));
  return d <= h + half;
}

}  // namespace

LidarSimulator::LidarSimulator(Scenario scenario) : s_(std::move(scenario)) {
  s_.sensor.validate();
  row_elev_ = s_.sensor.rowElevations();
  if (!s_.beam_elevation_error.empty() && s_.beam_elevation_error.size() != row_elev_.size())
    throw std::invalid_argument("beam_elevation_error: one entry per sensor row expected");
  if (!s_.beam_azimuth_error.empty() && s_.beam_azimuth_error.size() != row_elev_.size())
    throw std::invalid_argument("beam_azimuth_error: one entry per sensor row expected");
  for (std::size_t r = 0; r < s_.beam_elevation_error.size(); r++)
    row_elev_[r] += s_.beam_elevation_error[r];
}

std::int64_t LidarSimulator::timestampNs(int index) const {
  return std::llround(s_.start_time * 1e9) + std::llround(index * 1e9 / s_.sensor.frequency);
}

Eigen::Isometry3d LidarSimulator::robotPose(double t) const {
  const Pose2 p = s_.platform.at(t);
  const double f = std::min(1.0, s_.platform.speed(t) / 1.0);  // bobbing grows with speed
  const double w = 2 * M_PI * s_.bob_hz * t;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p.x, p.y, s_.bob_height * f * std::sin(w));
  T.linear() = (Eigen::AngleAxisd(p.yaw, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(s_.bob_pitch * f * std::cos(w), Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(s_.bob_roll * f * std::sin(0.5 * w), Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return T;
}

Eigen::Isometry3d LidarSimulator::sensorPose(double t) const {
  return robotPose(t) * Eigen::Translation3d(s_.mount);
}

void LidarSimulator::poseWorld(double t, std::vector<Posed>& out) const {
  out.clear();
  auto add = [&](const Part& p, int actor) {
    Posed q;
    q.part = p;
    q.actor = actor;
    q.uid = static_cast<std::uint32_t>(out.size());
    detail::boundingSphere(p, q.center, q.radius);
    out.push_back(q);
  };
  for (const Part& p : s_.statics) add(swayed(p, t, static_cast<std::uint32_t>(out.size())), -1);
  for (const Actor& a : s_.actors) {
    const Pose2 pose = a.track.at(t);
    if (!s_.realism.gait) {
      for (const Part& p : a.parts) add(placed(p, pose), a.id);
      continue;
    }
    const double speed = a.track.speed(t);  // limbs swing with the walking speed
    for (const Part& p : a.parts) add(placed(swung(p, t, speed, a.id), pose), a.id);
  }
}

SimulatedSweep LidarSimulator::simulate(int index) const {
  const core::SensorModel& sm = s_.sensor;
  const int H = sm.rows, W = sm.cols;
  SimulatedSweep sw;
  sw.index = index;
  sw.t = index * s_.period();
  sw.timestamp_ns = timestampNs(index);
  sw.robot_pose = robotPose(sw.t);
  sw.sensor_pose = sensorPose(sw.t);
  sw.actor = cv::Mat_<std::int16_t>(H, W, std::int16_t{-1});
  sw.dynamic = cv::Mat_<std::uint8_t>(H, W, std::uint8_t{0});

  std::mt19937 rng(s_.seed * 1000003u + static_cast<std::uint32_t>(index));
  std::uint64_t sweep_state = (static_cast<std::uint64_t>(s_.seed) << 32) ^
                              static_cast<std::uint64_t>(static_cast<std::uint32_t>(index));
  const std::uint64_t sweep_key = splitMix64(sweep_state);
  std::normal_distribution<double> gauss(0.0, 1.0);
  std::uniform_real_distribution<double> uni(0.0, 1.0);

  core::PointCloud cloud;
  cloud.reserve(static_cast<std::size_t>(H) * static_cast<std::size_t>(W), true, true);
  std::vector<std::int16_t> hit_actor;
  std::vector<std::uint8_t> hit_moving;
  hit_actor.reserve(cloud.x.capacity());
  hit_moving.reserve(cloud.x.capacity());
  const cv::Mat_<std::uint8_t> lost = lostPixels(sweep_key);
  std::vector<Posed> world;
  std::vector<const Posed*> cand;
  std::vector<double> moving_at(s_.actors.size(), 0);
  double world_t = -1;
  Eigen::Isometry3d T_ws = sw.sensor_pose;

  for (int c0 = 0; c0 < W; c0 += kGroup) {
    const int c1 = std::min(W, c0 + kGroup);
    // Firing time of this group: the head spins clockwise from azimuth +pi (column W-1).
    const double frac = (W - 0.5 * (c0 + c1)) / W;
    const double t = s_.motion_distortion ? sw.t + frac * s_.period() : sw.t;
    if (t != world_t) {
      poseWorld(t, world);
      T_ws = sensorPose(t);
      for (const Actor& a : s_.actors)
        moving_at[static_cast<std::size_t>(a.id)] = a.track.speed(t) > s_.moving_speed;
      world_t = t;
    }
    const Eigen::Isometry3d T_sw = T_ws.inverse();
    const double az_lo = -M_PI + c0 * 2 * M_PI / W, az_hi = -M_PI + c1 * 2 * M_PI / W;
    cand.clear();
    for (const Posed& p : world) {  // broad phase: bounding-sphere azimuth extent
      const Eigen::Vector3d cs = T_sw * p.center;
      const double dxy = std::hypot(cs.x(), cs.y());
      const double h = dxy <= p.radius ? M_PI : std::asin(p.radius / dxy);
      if (overlaps(std::atan2(cs.y(), cs.x()), h, az_lo, az_hi)) cand.push_back(&p);
    }
    const Eigen::Matrix3d R = T_ws.linear();
    Ray ray;
    ray.origin = T_ws.translation();
    for (int c = c0; c < c1; c++) {
      const double az = -M_PI + (c + 0.5) * 2 * M_PI / W;  // Eq. (1) column centre
      const double ca = std::cos(az), sa = std::sin(az);
      for (int r = 0; r < H; r++) {
        if (!lost.empty() && lost(r, c)) continue;
        const double el = row_elev_[static_cast<std::size_t>(r)];
        double cb = ca, sb = sa;  // this beam's azimuth: the column's, plus the unit's error
        if (!s_.beam_azimuth_error.empty()) {
          const double a = az + s_.beam_azimuth_error[static_cast<std::size_t>(r)];
          cb = std::cos(a);
          sb = std::sin(a);
        }
        const Eigen::Vector3d ds(std::cos(el) * cb, std::cos(el) * sb, std::sin(el));
        ray.dir = R * ds;
        Hit hit, best;
        const std::uint64_t pixel_key =
            sweep_key ^ (static_cast<std::uint64_t>(r * W + c) * 0xD6E8FEB86659FD93ULL);
        double t_max = sm.max_range;
        const Material* mat = nullptr;
        int actor = -1;
        if (intersect(s_.floor, ray, t_max, hit)) {
          best = hit;
          t_max = hit.t;
          mat = &s_.floor_material;
        }
        for (const Posed* p : cand)
          if (intersectPart(p->part, ray, t_max, pixel_key, p->uid, hit)) {
            best = hit;
            t_max = hit.t;
            mat = &p->part.material;
            actor = p->actor;
          }
        if (!mat || best.t < sm.min_range) continue;
        const double cosi = std::abs(best.normal.dot(ray.dir));
        const double refl =
            reflectivity(*mat, best.uv) * best.gain * (mat->retro ? kRetroGain : 1.0);
        const double beam_gain =
            s_.realism.beam_gain.empty() ? 1.0 : s_.realism.beam_gain[static_cast<std::size_t>(r)];
        const double expected = s_.intensity_gain * refl * (0.3 + 0.7 * cosi) *
                                rangeGain(best.t, s_.intensity_near_range) * beam_gain;
        if (uni(rng) < s_.dropout) continue;                    // random no-return
        if (cosi < s_.grazing_cos && uni(rng) < 0.8) continue;  // grazing incidence
        if (expected < 3.0) continue;                           // too weak to detect
        const double rng_m = best.t + s_.range_sigma * gauss(rng);
        if (rng_m <= sm.min_range || rng_m > sm.max_range) continue;
        double inten = 0;
        if (s_.intensity_model == IntensityModel::Ouster) {
          inten = std::max(0.0, std::round(expected * (1.0 + s_.intensity_noise * gauss(rng)) +
                                           std::sqrt(expected) * 0.5 * gauss(rng)));
        } else {  // Velodyne calibrated reflectivity: 100 = white diffuse, range-compensated
          const double v = 100.0 * refl * (0.4 + 0.6 * cosi) * beam_gain;
          inten = std::clamp(std::round(v * (1.0 + s_.intensity_noise * gauss(rng)) + gauss(rng)),
                             0.0, 255.0);
        }
        const Eigen::Vector3d p = ds * rng_m;
        cloud.push_back(static_cast<float>(p.x()), static_cast<float>(p.y()),
                        static_cast<float>(p.z()), static_cast<float>(inten),
                        static_cast<std::uint16_t>(r), static_cast<std::uint16_t>(c));
        hit_actor.push_back(static_cast<std::int16_t>(actor));
        hit_moving.push_back(actor >= 0 && moving_at[static_cast<std::size_t>(actor)]);
      }
    }
  }
  if (s_.realism.beam_divergence > 0 || s_.realism.interstitial > 0)
    mixEdges(cloud, hit_actor, hit_moving, sweep_key);

  core::SphericalProjection(sm).organize(cloud, sw.frame);
  sw.frame.timestamp_ns = sw.timestamp_ns;
  for (std::size_t i = 0; i < hit_actor.size(); i++) {
    sw.actor(cloud.row[i], cloud.col[i]) = hit_actor[i];
    if (hit_moving[i]) sw.dynamic(cloud.row[i], cloud.col[i]) = 255;
  }

  for (const Actor& a : s_.actors) {
    ActorState st;
    st.id = a.id;
    st.cls = a.cls;
    const Pose2 p = a.track.at(sw.t);
    double top = 0;
    for (const Part& part : a.parts)
      top = std::max(top, part.kind == Part::Kind::Box ? part.box.center.z() + part.box.half.z()
                                                       : part.cylinder.z1);
    st.position = {p.x, p.y, 0.5 * top};
    st.velocity = a.track.velocity(sw.t);
    st.moving = st.velocity.norm() > s_.moving_speed;
    st.points = cv::countNonZero(sw.actor == a.id);
    sw.actors.push_back(st);
  }
  return sw;
}

cv::Mat_<std::uint8_t> LidarSimulator::lostPixels(std::uint64_t sweep_key) const {
  const Realism& re = s_.realism;
  if (re.packet_loss <= 0 && re.dropout_runs <= 0) return {};
  const int H = s_.sensor.rows, W = s_.sensor.cols, P = re.packet_columns;
  cv::Mat_<std::uint8_t> lost(H, W, std::uint8_t{0});
  std::mt19937 rng(static_cast<std::uint32_t>(sweep_key ^ (sweep_key >> 32)) ^ 0x10575u);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  // Markov chain along the firing order (the head turns clockwise from column W-1): a run
  // starts with probability `start` and goes on with probability 1 - 1 / mean_length.
  const auto runs = [&](double start, double mean_length, int step, auto&& drop) {
    bool on = false;
    for (int first = W - 1; first >= 0; first -= step) {
      on = on ? uni(rng) >= 1.0 / mean_length : uni(rng) < start;
      if (on) drop(first);
    }
  };
  if (re.packet_loss > 0)
    runs(re.packet_loss, re.packet_burst, P, [&](int first) {
      for (int c = first; c > first - P && c >= 0; c--) lost.col(c).setTo(255);
    });
  if (re.dropout_runs > 0) {
    // A share d of the pixels in runs of mean length L: d = s L / (1 + s L) per start s.
    const double L = re.dropout_run_length, start = re.dropout_runs / (L * (1 - re.dropout_runs));
    for (int r = 0; r < H; r++) runs(start, L, 1, [&](int c) { lost(r, c) = 255; });
  }
  return lost;
}

void LidarSimulator::mixEdges(core::PointCloud& cloud, std::vector<std::int16_t>& actor,
                              std::vector<std::uint8_t>& moving, std::uint64_t sweep_key) const {
  const Realism& re = s_.realism;
  const int H = s_.sensor.rows, W = s_.sensor.cols;
  cv::Mat_<int> idx(H, W, -1);
  std::vector<double> range(cloud.size());
  for (std::size_t i = 0; i < cloud.size(); i++) {
    idx(cloud.row[i], cloud.col[i]) = static_cast<int>(i);
    range[i] = std::sqrt(double(cloud.x[i]) * cloud.x[i] + double(cloud.y[i]) * cloud.y[i] +
                         double(cloud.z[i]) * cloud.z[i]);
  }
  std::mt19937 rng(static_cast<std::uint32_t>(sweep_key ^ (sweep_key >> 32)) ^ 0x313Du);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double step = 2 * M_PI / W, half = 0.5 * re.beam_divergence;
  struct Change {
    int i, from;
    double f;  ///< share of point i's footprint on point `from`'s surface; < 0: interstitial at -f
  };
  std::vector<Change> changes;
  for (int r = 0; r < H; r++)
    for (int c = 0; c < W; c++) {
      const int a = idx(r, c), b = idx(r, (c + 1) % W);
      if (a < 0 || b < 0 || std::abs(range[a] - range[b]) < 0.05) continue;
      const double e = step * uni(rng);  // the edge, from a's beam centre towards b's
      const double fa = half > 0 ? std::clamp((half - e) / re.beam_divergence, 0.0, 0.5) : 0.0;
      const double fb =
          half > 0 ? std::clamp((half - (step - e)) / re.beam_divergence, 0.0, 0.5) : 0.0;
      if (re.interstitial > 0 && std::abs(range[a] - range[b]) >= re.echo_separation &&
          uni(rng) < re.interstitial) {
        // A point between the two surfaces (as measured on real sweeps: anywhere in between).
        changes.push_back({e < 0.5 * step ? a : b, e < 0.5 * step ? b : a, -uni(rng)});
        continue;
      }
      if (fa > 0) changes.push_back({a, b, fa});
      if (fb > 0) changes.push_back({b, a, fb});
    }
  // Every change reads the unmixed ranges; a point with an edge on both sides keeps the larger.
  std::sort(changes.begin(), changes.end(), [](const Change& x, const Change& y) {
    return x.i != y.i ? x.i < y.i : std::abs(x.f) > std::abs(y.f);
  });
  const std::vector<float> intensity = cloud.intensity;
  const std::vector<std::int16_t> actor0 = actor;
  const std::vector<std::uint8_t> moving0 = moving;
  for (std::size_t k = 0; k < changes.size(); k++) {
    if (k > 0 && changes[k].i == changes[k - 1].i) continue;
    const auto i = static_cast<std::size_t>(changes[k].i);
    const auto j = static_cast<std::size_t>(changes[k].from);
    double f = changes[k].f, r_new = range[i];
    if (f < 0) {  // interstitial: at a share -f of the way from the near surface to the far one
      const double near = std::min(range[i], range[j]), far = std::max(range[i], range[j]);
      r_new = near - f * (far - near);
      f = 0.5;
    } else {
      const double wi = (1 - f) * std::max(1.0f, intensity[i]);
      const double wj = f * std::max(1.0f, intensity[j]);
      if (std::abs(range[i] - range[j]) < re.echo_separation)  // one echo: energy-weighted range
        r_new = (wi * range[i] + wj * range[j]) / (wi + wj);
      else if (wj > wi)  // two echoes: the stronger is reported
        r_new = range[j];
    }
    if (r_new == range[i]) continue;
    const auto scale = static_cast<float>(r_new / range[i]);
    cloud.x[i] *= scale;
    cloud.y[i] *= scale;
    cloud.z[i] *= scale;
    cloud.intensity[i] = std::round((1 - f) * intensity[i] + f * intensity[j]);
    if (std::abs(r_new - range[j]) < std::abs(r_new - range[i])) {
      actor[i] = actor0[j];
      moving[i] = moving0[j];
    }
  }
}

}  // namespace dynobj::sim
