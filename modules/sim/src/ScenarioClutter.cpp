// SPDX-License-Identifier: BSD-3-Clause
// The scenario keys of real-world clutter (trees, bushes, fences) and of real sensor traits
// (intensity model, per-unit beam errors, output format). Format: docs/simulator.md.
#include <algorithm>
#include <cmath>

#include "ScenarioLoader.h"

namespace dynobj::sim::detail {
namespace {

/// Foliage: dark and noisy in LiDAR intensity (leaves are small, tilted, partly hit).
constexpr double kFoliageAlbedo = 0.15;

void loadSway(const YamlView& v, Part& p) {
  p.sway = v.num("sway", 0.05);
  p.sway_hz = v.num("sway_hz", 0.3);
  if (p.sway < 0) v.child("sway").fail("must be >= 0");
  if (p.sway > 0 && !(p.sway_hz > 0)) v.child("sway_hz").fail("must be > 0");
}

}  // namespace

void Loader::loadIntensity(const YamlView& root) {
  if (!root.has("intensity")) return;
  const YamlView n = root.child("intensity");
  n.onlyKeys({"model", "gain", "noise", "near_range"});
  const std::string model = n.str("model", "ouster");
  if (model == "ouster")
    s_.intensity_model = IntensityModel::Ouster;
  else if (model == "velodyne")
    s_.intensity_model = IntensityModel::Velodyne;
  else
    n.child("model").fail("unknown intensity model '" + model + "' (ouster, velodyne)");
  s_.intensity_gain = n.num("gain", s_.intensity_gain);
  s_.intensity_near_range = n.num("near_range", s_.intensity_near_range);
  s_.intensity_noise = n.num("noise", s_.intensity_noise);
}

void Loader::loadSensorUnit(const YamlView& root) {
  if (!root.has("sensor_unit")) return;
  const YamlView u = root.child("sensor_unit");
  u.onlyKeys({"elevation_sigma_deg", "azimuth_sigma_deg", "seed"});
  const double se = u.num("elevation_sigma_deg", 0.0) * kDeg;
  const double sa = u.num("azimuth_sigma_deg", 0.0) * kDeg;
  if (se < 0) u.child("elevation_sigma_deg").fail("must be >= 0");
  if (sa < 0) u.child("azimuth_sigma_deg").fail("must be >= 0");
  // Its own generator: a unit's errors do not shift the other draws of the scenario.
  std::mt19937 rng(static_cast<std::uint32_t>(u.num("seed", s_.seed)) ^ 0x5E750Bu);
  std::normal_distribution<double> g(0.0, 1.0);
  const auto rows = static_cast<std::size_t>(s_.sensor.rows);
  s_.beam_elevation_error.assign(rows, 0.0);
  s_.beam_azimuth_error.assign(rows, 0.0);
  for (std::size_t r = 0; r < rows; r++) {
    s_.beam_elevation_error[r] = se * g(rng);
    s_.beam_azimuth_error[r] = sa * g(rng);
  }
}

void Loader::loadRealism(const YamlView& root) {
  if (!root.has("realism")) return;
  const YamlView v = root.child("realism");
  Realism& r = s_.realism;
  // Column firings in one data packet: an Ouster packet holds 16 columns; a Velodyne packet 12
  // blocks of 32 lasers (VLP-16: 24 columns, HDL-32E 12, HDL-64E 6, VLS-128 3).
  r.packet_columns = s_.intensity_model == IntensityModel::Velodyne
                         ? std::max(1, 384 / std::max(1, s_.sensor.rows))
                         : 16;
  const bool velodyne = s_.intensity_model == IntensityModel::Velodyne;
  const auto harsh = [&r, velodyne] {  // defaults measured on real captures: docs/simulator.md
    r.beam_divergence = 3.0e-3;
    r.interstitial = 0.07;
    r.beam_gain_sigma = velodyne ? 0.18 : 0.09;
    r.retro_reflectors = true;
    r.dropout_runs = 0.04;
    r.gait = true;
    r.body_motion = 0.15 * kDeg;
  };
  const auto profile = [&](const YamlView& p) {
    const std::string name = p.scalar();
    if (name == "harsh")
      harsh();
    else if (name != "none")
      p.fail("unknown realism profile '" + name + "' (none, harsh)");
  };
  if (!v.isMap()) {
    profile(v);
  } else {
    v.onlyKeys({"profile", "beam_divergence_mrad", "echo_separation", "interstitial",
                "beam_gain_sigma", "retro_reflectors", "dropout_runs", "dropout_run_length",
                "packet_loss", "packet_burst", "gait", "body_motion_deg", "seed"});
    if (v.has("profile")) profile(v.child("profile"));
    r.beam_divergence = v.num("beam_divergence_mrad", r.beam_divergence * 1e3) * 1e-3;
    r.echo_separation = v.num("echo_separation", r.echo_separation);
    r.interstitial = v.num("interstitial", r.interstitial);
    r.beam_gain_sigma = v.num("beam_gain_sigma", r.beam_gain_sigma);
    r.retro_reflectors = v.flag("retro_reflectors", r.retro_reflectors);
    r.dropout_runs = v.num("dropout_runs", r.dropout_runs);
    r.dropout_run_length = v.num("dropout_run_length", r.dropout_run_length);
    r.packet_loss = v.num("packet_loss", r.packet_loss);
    r.packet_burst = v.num("packet_burst", r.packet_burst);
    r.gait = v.flag("gait", r.gait);
    r.body_motion = v.num("body_motion_deg", r.body_motion / kDeg) * kDeg;
    if (r.body_motion < 0) v.child("body_motion_deg").fail("must be >= 0");
    const auto share = [&v](const char* key, double x) {
      if (!(x >= 0 && x < 1)) v.child(key).fail("must be in [0, 1)");
    };
    if (r.beam_divergence < 0) v.child("beam_divergence_mrad").fail("must be >= 0");
    if (!(r.echo_separation > 0)) v.child("echo_separation").fail("must be > 0");
    share("interstitial", r.interstitial);
    if (r.beam_gain_sigma < 0) v.child("beam_gain_sigma").fail("must be >= 0");
    share("dropout_runs", r.dropout_runs);
    if (!(r.dropout_run_length >= 1)) v.child("dropout_run_length").fail("must be >= 1");
    share("packet_loss", r.packet_loss);
    if (!(r.packet_burst >= 1)) v.child("packet_burst").fail("must be >= 1");
  }
  if (r.beam_gain_sigma > 0) {  // its own generator, as for sensor_unit
    const auto seed = static_cast<std::uint32_t>(v.isMap() ? v.num("seed", s_.seed) : s_.seed);
    std::mt19937 rng(seed ^ 0x6A1Bu);
    std::normal_distribution<double> g(0.0, 1.0);
    r.beam_gain.resize(static_cast<std::size_t>(s_.sensor.rows));
    for (double& k : r.beam_gain) k = std::exp(r.beam_gain_sigma * g(rng));
  }
}

void Loader::loadOutput(const YamlView& root) {
  const std::string f = root.str("output", "range_scan");
  if (f == "range_scan")
    s_.output = OutputFormat::RangeScan;
  else if (f == "point_cloud")
    s_.output = OutputFormat::PointCloud;
  else
    root.child("output").fail("unknown output '" + f + "' (range_scan, point_cloud)");
}

void Loader::loadTree(const YamlView& item) {
  item.onlyKeys({"tree", "material", "foliage"});
  const YamlView t = item.child("tree");
  t.onlyKeys({"center", "height", "trunk_radius", "crown_radius", "crown_height", "density", "sway",
              "sway_hz"});
  const Eigen::Vector2d c = vec2(t, "center");
  const double h = drawRange(t, "height", 6.0, rng_);
  const double crown_r = drawRange(t, "crown_radius", 0.3 * h, rng_);
  const double crown_h = drawRange(t, "crown_height", 0.55 * h, rng_);
  const double trunk_r = positive(t, "trunk_radius", 0.15);
  if (!(h > 0)) t.child("height").fail("must be > 0");
  if (!(crown_r > 0)) t.child("crown_radius").fail("must be > 0");
  if (!(crown_h > 0 && crown_h <= h)) t.child("crown_height").fail("must be in (0, height]");
  Part trunk;
  trunk.kind = Part::Kind::Cylinder;
  trunk.cylinder = {c, trunk_r, 0.0, h - 0.5 * crown_h};
  trunk.material = material(item, 0.3, Pattern::Noise, 0.2);
  s_.statics.push_back(trunk);
  Part crown;
  crown.kind = Part::Kind::Porous;
  crown.porous.center = {c.x(), c.y(), h - 0.5 * crown_h};
  crown.porous.half = {crown_r, crown_r, 0.5 * crown_h};
  crown.porous.density = positive(t, "density", 1.2);
  crown.material = material(item, kFoliageAlbedo, Pattern::Noise, 0.3, "foliage");
  if (!(item.has("foliage") && item.child("foliage").has("contrast")))
    crown.material.contrast = 0.8;
  loadSway(t, crown);
  s_.statics.push_back(crown);
}

void Loader::loadBush(const YamlView& item) {
  item.onlyKeys({"bush", "material"});
  const YamlView b = item.child("bush");
  b.onlyKeys({"center", "size", "yaw_deg", "shape", "density", "sway", "sway_hz"});
  const Eigen::Vector2d c = vec2(b, "center");
  const auto sz = b.nums("size", 3);
  for (double v : sz)
    if (!(v > 0)) b.child("size").fail("sizes must be > 0");
  Part p;
  p.kind = Part::Kind::Porous;
  const std::string shape = b.str("shape", "ellipsoid");
  if (shape != "ellipsoid" && shape != "box")
    b.child("shape").fail("unknown shape '" + shape + "' (ellipsoid, box)");
  p.porous.ellipsoid = shape == "ellipsoid";
  p.porous.center = {c.x(), c.y(), sz[2] / 2};
  p.porous.half = {sz[0] / 2, sz[1] / 2, sz[2] / 2};
  p.porous.yaw = b.num("yaw_deg", 0) * kDeg;
  p.porous.density = positive(b, "density", 2.5);
  p.material = material(item, kFoliageAlbedo, Pattern::Noise, 0.3);
  if (!(item.has("material") && item.child("material").has("contrast"))) p.material.contrast = 0.8;
  loadSway(b, p);
  if (!b.has("sway")) p.sway = 0.02;  // low and stiff: barely moves
  s_.statics.push_back(p);
}

void Loader::loadFence(const YamlView& item) {
  item.onlyKeys({"fence", "material"});
  const YamlView f = item.child("fence");
  f.onlyKeys({"from", "to", "height", "style", "bar_width", "bar_spacing", "rail_width",
              "rail_spacing", "rails"});
  Part p;
  p.kind = Part::Kind::Fence;
  Fence& fe = p.fence;
  fe.a = vec2(f, "from");
  fe.b = vec2(f, "to");
  if ((fe.b - fe.a).norm() < 1e-3) f.child("to").fail("must differ from 'from'");
  fe.z0 = 0;
  fe.z1 = positive(f, "height", 1.2);
  const std::string style = f.str("style", "bars");
  std::vector<double> rails;
  if (style == "bars") {  // palisade: vertical bars, a bottom and a top rail
    fe.bar_width = 0.03;
    fe.bar_spacing = 0.12;
    rails = {0.1, fe.z1 - 0.03};
  } else if (style == "railing") {  // posts and two rails: mostly see-through
    fe.bar_width = 0.05;
    fe.bar_spacing = 1.5;
    rails = {0.5 * fe.z1, fe.z1 - 0.03};
  } else if (style == "mesh") {  // chain-link / wire mesh: thin wires both ways
    fe.bar_width = 0.004;
    fe.bar_spacing = 0.05;
    fe.rail_width = 0.004;
    fe.rail_spacing = 0.05;
    rails = {fe.z1 - 0.02};
  } else {
    f.child("style").fail("unknown fence style '" + style + "' (bars, railing, mesh)");
  }
  fe.bar_width = f.num("bar_width", fe.bar_width);
  fe.bar_spacing = f.num("bar_spacing", fe.bar_spacing);
  fe.rail_width = f.num("rail_width", fe.rail_width);
  fe.rail_spacing = f.num("rail_spacing", fe.rail_spacing);
  if (f.has("rails")) rails = f.nums("rails");
  if (rails.size() > fe.rails.size())
    f.child("rails").fail("at most " + std::to_string(fe.rails.size()) + " rails");
  if (fe.bar_width < 0 || fe.bar_spacing < 0) f.fail("bar_width and bar_spacing must be >= 0");
  if (fe.rail_width < 0 || fe.rail_spacing < 0) f.fail("rail_width and rail_spacing must be >= 0");
  fe.rail_count = static_cast<int>(rails.size());
  for (std::size_t i = 0; i < rails.size(); i++) fe.rails[i] = rails[i];
  p.material = material(item, 0.5, Pattern::Plain, 1.0);
  s_.statics.push_back(p);
}

}  // namespace dynobj::sim::detail
