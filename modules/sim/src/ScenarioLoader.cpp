// SPDX-License-Identifier: BSD-3-Clause
#include "ScenarioLoader.h"

#include <dynobj/io/SensorFile.h>

#include <cmath>

namespace dynobj::sim::detail {

std::pair<double, double> rangeOf(const YamlView& v, const std::string& key, double lo, double hi,
                                  bool* is_range) {
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

double drawRange(const YamlView& v, const std::string& key, double def, std::mt19937& rng) {
  bool is_range = false;
  const auto [lo, hi] = rangeOf(v, key, def, def, &is_range);
  return is_range ? std::uniform_real_distribution<double>(lo, hi)(rng) : lo;
}

Eigen::Vector2d vec2(const YamlView& v, const std::string& key) {
  const auto n = v.nums(key, 2);
  return {n[0], n[1]};
}

double positive(const YamlView& v, const std::string& key, double def) {
  const double x = v.num(key, def);
  if (!(x > 0)) v.child(key).fail("must be > 0");
  return x;
}

void Loader::load(const YamlView& root) {
  root.onlyKeys({"name",         "seed",         "frames",     "start_time",
                 "sensor",       "sensor_label", "mount",      "noise",
                 "intensity",    "sensor_unit",  "output",     "motion_distortion",
                 "moving_speed", "odometry",     "floor",      "static",
                 "actors",       "platform",     "procedural", "realism"});
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
  loadIntensity(root);
  loadSensorUnit(root);
  loadOutput(root);
  loadRealism(root);
  s_.motion_distortion = root.flag("motion_distortion", s_.motion_distortion);
  s_.moving_speed = root.num("moving_speed", s_.moving_speed);
  if (root.has("odometry")) {
    const YamlView o = root.child("odometry");
    o.onlyKeys({"enabled", "sigma_xy", "sigma_yaw_deg"});
    s_.odometry = o.flag("enabled", s_.odometry);
    s_.odometry_sigma_xy = o.num("sigma_xy", s_.odometry_sigma_xy);
    s_.odometry_sigma_yaw = o.num("sigma_yaw_deg", s_.odometry_sigma_yaw / kDeg) * kDeg;
  }
  // A procedural world comes first; the file's own floor and platform replace the generated
  // ones, its static objects and actors are added to them.
  const YamlView* world = loadProcedural(root);
  loadFloor(root.has("floor") || !world ? root : *world);
  for (const YamlView* src : {world, &root})
    if (src && src->has("static"))
      for (const auto& item : src->seq("static")) loadStatic(item);
  if (world && !root.has("platform")) {
    loadPlatform(world->child("platform"), world->child("platform"));
  } else {
    const YamlView p = root.child("platform");
    loadPlatform(p, p.has("trajectory") || !world ? p : world->child("platform"));
  }
  const double sway = s_.realism.body_motion;
  if (sway > 0 && s_.bob_roll == 0 && s_.bob_pitch == 0 && s_.bob_height == 0) {
    // A vehicle's body rolling and pitching on its suspension (1.5 Hz): amplitudes giving
    // per-sweep changes of standard deviation `body_motion` at 10 Hz (robotPose()).
    s_.bob_hz = 1.5;
    const double step = 2 * M_PI * s_.bob_hz * 0.1 / std::sqrt(2.0);
    s_.bob_pitch = sway / step;
    s_.bob_roll = sway / (0.5 * step);
    s_.bob_height = 0.01;
  }
  for (const YamlView* src : {world, &root})
    if (src && src->has("actors"))
      for (const auto& item : src->seq("actors")) loadActors(item);
}

void Loader::loadSensor(const YamlView& root) {
  const std::string rel = root.str("sensor", "sensors/os0-64.ini");
  const std::string path = rel.front() == '/' ? rel : share_ + "/" + rel;
  try {
    s_.sensor = io::readSensorModel(path);
  } catch (const std::exception& e) {
    (root.has("sensor") ? root.child("sensor") : root).fail(e.what());
  }
}

Material Loader::material(const YamlView& owner, double albedo, Pattern pattern, double scale,
                          const std::string& key) {
  Material m;
  m.albedo = albedo;
  m.pattern = pattern;
  m.scale = scale;
  m.seed = s_.seed * 7919u + ++surfaces_;
  if (!owner.has(key)) return m;
  const YamlView v = owner.child(key);
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

void Loader::loadFloor(const YamlView& root) {
  if (!root.has("floor")) return;
  const YamlView f = root.child("floor");
  f.onlyKeys({"size", "center", "material"});
  const Eigen::Vector2d size = vec2(f, "size");
  const Eigen::Vector2d c = f.has("center") ? vec2(f, "center") : Eigen::Vector2d(0, 0);
  s_.floor = {0.0, c.x() - size.x() / 2, c.x() + size.x() / 2, c.y() - size.y() / 2,
              c.y() + size.y() / 2};
  s_.floor_material = material(f, 0.25, Pattern::Markings, 1.5);
}

void Loader::loadStatic(const YamlView& item) {
  if (item.has("tree")) return loadTree(item);
  if (item.has("bush")) return loadBush(item);
  if (item.has("fence")) return loadFence(item);
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
    for (Part p :
         actorBody(ActorClass::Car, 1.5, material(item, 0.35, Pattern::Noise, 0.5), s_.realism)) {
      const Eigen::Vector3d local = p.box.center;
      p.box.center = {c.x() + std::cos(yaw) * local.x() - std::sin(yaw) * local.y(),
                      c.y() + std::sin(yaw) * local.x() + std::cos(yaw) * local.y(), local.z()};
      p.box.yaw += yaw;
      s_.statics.push_back(p);
    }
  } else {
    item.fail("a static object needs one of: box, cylinder, car, tree, bush, fence");
  }
}

PoseTrack Loader::track(const YamlView& t, double start) {
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

void Loader::loadPlatform(const YamlView& p, const YamlView& trajectory_owner) {
  p.onlyKeys({"trajectory", "bob"});
  s_.platform = track(trajectory_owner.child("trajectory"), 0.0);
  if (p.has("bob")) {
    const YamlView b = p.child("bob");
    b.onlyKeys({"height", "roll_deg", "pitch_deg", "hz"});
    s_.bob_height = b.num("height", 0.02);
    s_.bob_roll = b.num("roll_deg", 1.0) * kDeg;
    s_.bob_pitch = b.num("pitch_deg", 1.5) * kDeg;
    s_.bob_hz = b.num("hz", 1.8);
  }
}

void Loader::loadActors(const YamlView& a) {
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
    actor.parts = actorBody(cls, h, material(a, 0.35, Pattern::Noise, 0.15), s_.realism);
    actor.track = track(t, start);
    s_.actors.push_back(std::move(actor));
  }
}

}  // namespace dynobj::sim::detail
