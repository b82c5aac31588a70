// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/Scenario.h"

#include <dynobj/core/Config.h>
#include <dynobj/io/SensorFile.h>
#include <mrpt/containers/yaml.h>

#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "YamlView.h"

namespace dynobj::sim {
namespace {

using detail::YamlView;
constexpr double kDeg = M_PI / 180.0;

/// A value given as one number or as a [lo, hi] range (is_range tells which).
std::pair<double, double> rangeOf(const YamlView& v, const std::string& key, double lo, double hi,
                                  bool* is_range = nullptr) {
  if (is_range) *is_range = false;
  if (!v.has(key)) return {lo, hi};
  const YamlView c = v.child(key);
  if (!c.isSequence()) {
    const double x = c.number();
    return {x, x};
  }
  const auto r = c.numbers();
  if (r.size() != 2 || r[1] < r[0]) c.fail("expected a number or [lo, hi]");
  if (is_range) *is_range = true;
  return {r[0], r[1]};
}

/// rangeOf(), drawn uniformly when a range.
double drawRange(const YamlView& v, const std::string& key, double def, std::mt19937& rng) {
  bool is_range = false;
  const auto [lo, hi] = rangeOf(v, key, def, def, &is_range);
  return is_range ? std::uniform_real_distribution<double>(lo, hi)(rng) : lo;
}

Eigen::Vector2d vec2(const YamlView& v, const std::string& key) {
  const auto n = v.nums(key, 2);
  return {n[0], n[1]};
}

class Loader {
 public:
  Loader(Scenario& s, std::string share_dir) : s_(s), share_(std::move(share_dir)) {}

  void load(const YamlView& root) {
    root.onlyKeys({"name", "seed", "frames", "start_time", "sensor", "sensor_label", "mount",
                   "noise", "intensity", "motion_distortion", "moving_speed", "odometry", "floor",
                   "static", "actors", "platform"});
    s_.name = root.str("name", s_.name);
    s_.seed = static_cast<std::uint32_t>(root.num("seed", s_.seed));
    s_.frames = static_cast<int>(root.num("frames", s_.frames));
    if (s_.frames < 1) root.child("frames").fail("must be >= 1");
    s_.start_time = root.num("start_time", s_.start_time);
    rng_.seed(s_.seed);
    loadSensor(root);
    s_.sensor_label = root.str("sensor_label", s_.sensor_label);
    if (root.has("mount")) {
      const auto m = root.nums("mount", 3);
      s_.mount = {m[0], m[1], m[2]};
    }
    if (root.has("noise")) {
      const YamlView n = root.child("noise");
      n.onlyKeys({"range_sigma", "dropout", "grazing_cos"});
      s_.range_sigma = n.num("range_sigma", s_.range_sigma);
      s_.dropout = n.num("dropout", s_.dropout);
      s_.grazing_cos = n.num("grazing_cos", s_.grazing_cos);
    }
    if (root.has("intensity")) {
      const YamlView n = root.child("intensity");
      n.onlyKeys({"gain", "noise", "near_range"});
      s_.intensity_gain = n.num("gain", s_.intensity_gain);
      s_.intensity_near_range = n.num("near_range", s_.intensity_near_range);
      s_.intensity_noise = n.num("noise", s_.intensity_noise);
    }
    s_.motion_distortion = root.flag("motion_distortion", s_.motion_distortion);
    s_.moving_speed = root.num("moving_speed", s_.moving_speed);
    if (root.has("odometry")) {
      const YamlView o = root.child("odometry");
      o.onlyKeys({"enabled", "sigma_xy", "sigma_yaw_deg"});
      s_.odometry = o.flag("enabled", s_.odometry);
      s_.odometry_sigma_xy = o.num("sigma_xy", s_.odometry_sigma_xy);
      s_.odometry_sigma_yaw = o.num("sigma_yaw_deg", s_.odometry_sigma_yaw / kDeg) * kDeg;
    }
    loadFloor(root);
    if (root.has("static"))
      for (const auto& item : root.seq("static")) loadStatic(item);
    loadPlatform(root.child("platform"));
    if (root.has("actors"))
      for (const auto& item : root.seq("actors")) loadActors(item);
  }

 private:
  void loadSensor(const YamlView& root) {
    const std::string rel = root.str("sensor", "sensors/os0-64.ini");
    const std::string path = rel.front() == '/' ? rel : share_ + "/" + rel;
    try {
      s_.sensor = io::readSensorModel(path);
    } catch (const std::exception& e) {
      (root.has("sensor") ? root.child("sensor") : root).fail(e.what());
    }
  }

  Material material(const YamlView& owner, double albedo, Pattern pattern, double scale) {
    Material m;
    m.albedo = albedo;
    m.pattern = pattern;
    m.scale = scale;
    m.seed = s_.seed * 7919u + ++surfaces_;
    if (!owner.has("material")) return m;
    const YamlView v = owner.child("material");
    v.onlyKeys({"albedo", "pattern", "scale", "contrast"});
    m.albedo = v.num("albedo", m.albedo);
    if (v.has("pattern")) {
      try {
        m.pattern = patternFromString(v.child("pattern").scalar());
      } catch (const std::invalid_argument& e) {
        v.child("pattern").fail(e.what());
      }
    }
    m.scale = v.num("scale", m.scale);
    m.contrast = v.num("contrast", m.contrast);
    if (!(m.albedo > 0 && m.albedo <= 1)) v.child("albedo").fail("must be in (0, 1]");
    return m;
  }

  void loadFloor(const YamlView& root) {
    if (!root.has("floor")) return;
    const YamlView f = root.child("floor");
    f.onlyKeys({"size", "center", "material"});
    const Eigen::Vector2d size = vec2(f, "size");
    const Eigen::Vector2d c = f.has("center") ? vec2(f, "center") : Eigen::Vector2d(0, 0);
    s_.floor = {0.0, c.x() - size.x() / 2, c.x() + size.x() / 2, c.y() - size.y() / 2,
                c.y() + size.y() / 2};
    s_.floor_material = material(f, 0.25, Pattern::Markings, 1.5);
  }

  void loadStatic(const YamlView& item) {
    item.onlyKeys({"box", "cylinder", "car", "material"});
    if (item.has("box")) {
      const YamlView b = item.child("box");
      b.onlyKeys({"center", "size", "yaw_deg"});
      Part p;
      p.kind = Part::Kind::Box;
      const auto c = b.nums("center", 3), sz = b.nums("size", 3);
      p.box = {{c[0], c[1], c[2]}, {sz[0] / 2, sz[1] / 2, sz[2] / 2}, b.num("yaw_deg", 0) * kDeg};
      p.material = material(item, 0.4, Pattern::Noise, 1.0);
      s_.statics.push_back(p);
    } else if (item.has("cylinder")) {
      const YamlView b = item.child("cylinder");
      b.onlyKeys({"center", "radius", "height"});
      Part p;
      p.kind = Part::Kind::Cylinder;
      const Eigen::Vector2d c = vec2(b, "center");
      p.cylinder = {c, b.numRequired("radius"), 0.0, b.numRequired("height")};
      p.material = material(item, 0.4, Pattern::Stripes, 0.3);
      s_.statics.push_back(p);
    } else if (item.has("car")) {  // a parked vehicle: a car body that never moves
      const YamlView b = item.child("car");
      b.onlyKeys({"center", "yaw_deg"});
      const Eigen::Vector2d c = vec2(b, "center");
      const double yaw = b.num("yaw_deg", 0) * kDeg;
      for (Part p : actorBody(ActorClass::Car, 1.5, material(item, 0.35, Pattern::Noise, 0.5))) {
        const Eigen::Vector3d local = p.box.center;
        p.box.center = {c.x() + std::cos(yaw) * local.x() - std::sin(yaw) * local.y(),
                        c.y() + std::sin(yaw) * local.x() + std::cos(yaw) * local.y(), local.z()};
        p.box.yaw += yaw;
        s_.statics.push_back(p);
      }
    } else {
      item.fail("a static object needs one of: box, cylinder, car");
    }
  }

  PoseTrack track(const YamlView& t, double start) {
    t.onlyKeys(
        {"type", "points", "speed", "pause", "loop", "start", "region", "from", "at", "yaw_deg"});
    const std::string type = t.str("type", "waypoints");
    try {
      if (type == "stationary") {
        const Eigen::Vector2d at = vec2(t, "at");
        return PoseTrack::stationary({at.x(), at.y(), t.num("yaw_deg", 0) * kDeg});
      }
      if (type == "waypoints") {
        std::vector<Eigen::Vector2d> pts;
        for (const auto& p : t.seq("points")) {
          const auto xy = p.numbers();
          if (xy.size() != 2) p.fail("expected [x, y]");
          pts.emplace_back(xy[0], xy[1]);
        }
        return PoseTrack::waypoints(pts, t.num("speed", 1.0), drawRange(t, "pause", 0.0, rng_),
                                    t.flag("loop", true), start, s_.duration());
      }
      if (type == "random_walk") {
        const auto r = t.nums("region", 4);
        const Eigen::Vector4d region(r[0], r[1], r[2], r[3]);
        Eigen::Vector2d from;
        if (t.has("from")) {
          from = vec2(t, "from");
        } else {
          from = {std::uniform_real_distribution<double>(r[0], r[2])(rng_),
                  std::uniform_real_distribution<double>(r[1], r[3])(rng_)};
        }
        const auto [slo, shi] = rangeOf(t, "speed", 0.5, 1.5);
        const auto [plo, phi] = rangeOf(t, "pause", 0.0, 0.0);
        return PoseTrack::randomWalk(region, from, slo, shi, plo, phi, start, s_.duration(), rng_);
      }
    } catch (const std::invalid_argument& e) {
      t.fail(e.what());
    }
    t.child("type").fail("unknown trajectory type '" + type +
                         "' (stationary, waypoints, random_walk)");
  }

  void loadPlatform(const YamlView& p) {
    p.onlyKeys({"trajectory", "bob"});
    s_.platform = track(p.child("trajectory"), 0.0);
    if (p.has("bob")) {
      const YamlView b = p.child("bob");
      b.onlyKeys({"height", "roll_deg", "pitch_deg", "hz"});
      s_.bob_height = b.num("height", 0.02);
      s_.bob_roll = b.num("roll_deg", 1.0) * kDeg;
      s_.bob_pitch = b.num("pitch_deg", 1.5) * kDeg;
      s_.bob_hz = b.num("hz", 1.8);
    }
  }

  void loadActors(const YamlView& a) {
    a.onlyKeys({"class", "count", "height", "trajectory", "material"});
    const std::string cls_name = a.str("class", "pedestrian");
    ActorClass cls = ActorClass::Pedestrian;
    if (cls_name == "cyclist")
      cls = ActorClass::Cyclist;
    else if (cls_name == "car")
      cls = ActorClass::Car;
    else if (cls_name != "pedestrian")
      a.child("class").fail("unknown class '" + cls_name + "' (pedestrian, cyclist, car)");
    const int count = static_cast<int>(a.num("count", 1));
    if (count < 1) a.child("count").fail("must be >= 1");
    const double default_h =
        cls == ActorClass::Car ? 1.5 : (cls == ActorClass::Cyclist ? 1.75 : 1.75);
    const YamlView t = a.child("trajectory");
    for (int k = 0; k < count; k++) {
      Actor actor;
      actor.id = static_cast<int>(s_.actors.size());
      actor.cls = cls;
      const double h = drawRange(a, "height", default_h, rng_);
      const double start = drawRange(t, "start", 0.0, rng_);
      actor.parts = actorBody(cls, h, material(a, 0.35, Pattern::Noise, 0.15));
      actor.track = track(t, start);
      s_.actors.push_back(std::move(actor));
    }
  }

  Scenario& s_;
  std::string share_;
  std::mt19937 rng_;
  std::uint32_t surfaces_ = 0;
};

void applyOverride(::mrpt::containers::yaml& doc, const std::string& key,
                   const std::string& value) {
  std::vector<std::string> parts;
  std::stringstream ss(key);
  std::string p;
  while (std::getline(ss, p, '.')) parts.push_back(p);
  if (parts.empty()) throw ScenarioError("empty override key");
  ::mrpt::containers::yaml::node_t* node = &doc.node();
  for (std::size_t i = 0; i < parts.size(); i++) {
    if (!node->isMap())
      throw ScenarioError("override '" + key + "': '" + parts[i] + "' is not in a map");
    auto& map = node->asMap();
    ::mrpt::containers::yaml::node_t k;
    k.d.emplace<::mrpt::containers::yaml::scalar_t>(parts[i]);
    if (i + 1 == parts.size()) {
      ::mrpt::containers::yaml::node_t v;
      v.d.emplace<::mrpt::containers::yaml::scalar_t>(value);
      map[k] = v;
    } else {
      if (!map.count(k)) throw ScenarioError("override '" + key + "': no key '" + parts[i] + "'");
      node = &map[k];
    }
  }
}

}  // namespace

const char* toString(ActorClass c) {
  switch (c) {
    case ActorClass::Pedestrian:
      return "pedestrian";
    case ActorClass::Cyclist:
      return "cyclist";
    case ActorClass::Car:
      return "car";
  }
  return "?";
}

std::vector<Part> actorBody(ActorClass cls, double height, const Material& material) {
  std::vector<Part> parts;
  auto box = [&](double x, double y, double z, double sx, double sy, double sz) {
    Part p;
    p.kind = Part::Kind::Box;
    p.box = {{x, y, z}, {sx / 2, sy / 2, sz / 2}, 0.0};
    p.material = material;
    parts.push_back(p);
  };
  auto cyl = [&](double x, double y, double r, double z0, double z1, double albedo_scale) {
    Part p;
    p.kind = Part::Kind::Cylinder;
    p.cylinder = {{x, y}, r, z0, z1};
    p.material = material;
    p.material.albedo = std::clamp(material.albedo * albedo_scale, 0.02, 1.0);
    parts.push_back(p);
  };
  const double s = height / 1.75;
  switch (cls) {
    case ActorClass::Pedestrian:  // legs, torso, head (different albedos: clothes vs skin)
      cyl(0, 0.1, 0.08 * s, 0.0, 0.85 * s, 0.7);
      cyl(0, -0.1, 0.08 * s, 0.0, 0.85 * s, 0.7);
      cyl(0, 0, 0.2 * s, 0.85 * s, 1.5 * s, 1.0);
      cyl(0, 0, 0.1 * s, 1.52 * s, 1.75 * s, 1.6);
      break;
    case ActorClass::Cyclist:
      box(0, 0, 0.5, 1.7, 0.12, 0.9);  // bicycle
      cyl(-0.1, 0, 0.22, 0.95, 1.55 * s, 1.0);
      cyl(-0.05, 0, 0.11, 1.55 * s, 1.78 * s, 1.6);
      break;
    case ActorClass::Car:
      box(0, 0, 0.3 + 0.5 * s, 4.4, 1.8, 1.0 * s);        // body
      box(-0.3, 0, 0.3 + 1.225 * s, 2.4, 1.6, 0.45 * s);  // cabin on top of the body
      break;
  }
  return parts;
}

Scenario Scenario::fromYamlText(const std::string& text, const std::string& share_dir,
                                const std::map<std::string, std::string>& overrides,
                                const std::string& source) {
  ::mrpt::containers::yaml doc;
  try {
    doc = ::mrpt::containers::yaml::FromText(text);
  } catch (const std::exception& e) {
    std::string msg = e.what();
    const auto nl = msg.find("\nCall stack");
    throw ScenarioError(source + ": not valid YAML: " + msg.substr(0, nl));
  }
  Scenario s;
  try {
    if (!doc.isMap())
      throw detail::ScenarioError(
          "not valid YAML, or not a map of key: value (the YAML parser's "
          "message, if any, is printed above)");
    for (const auto& [k, v] : overrides) applyOverride(doc, k, v);
    Loader(s, share_dir).load(YamlView(&doc.node(), ""));
  } catch (const detail::ScenarioError& e) {
    throw ScenarioError(source + ": " + e.what());
  } catch (const ScenarioError& e) {
    throw ScenarioError(source + ": " + e.what());
  }
  return s;
}

Scenario Scenario::fromYamlFile(const std::string& path, const std::string& share_dir,
                                const std::map<std::string, std::string>& overrides) {
  std::ifstream in(path);
  if (!in) throw ScenarioError("cannot open scenario file '" + path + "'");
  std::stringstream ss;
  ss << in.rdbuf();
  return fromYamlText(ss.str(), share_dir, overrides, path);
}

}  // namespace dynobj::sim
