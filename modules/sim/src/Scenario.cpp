// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/Scenario.h"

#include <dynobj/core/Config.h>
#include <mrpt/containers/yaml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>

#include "ScenarioLoader.h"
#include "YamlView.h"

namespace dynobj::sim {
namespace {

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
      // A missing block is created (e.g. --set noise.range_sigma=0.05 on a scenario without
      // `noise:`); a misspelt one is then reported by the loader as an unknown key.
      if (!map.count(k)) map[k] = ::mrpt::containers::yaml::Map();
      node = &map[k];
    }
  }
}

/// Byte offset of the first byte that is not well-formed UTF-8 (RFC 3629), or npos. YAML text
/// must be UTF-8, and libfyaml 0.8 (under MRPT's yaml) loops forever on a malformed byte inside
/// a `%` directive (found by fuzz_scenario_yaml): the text is checked before it is parsed.
std::size_t firstInvalidUtf8(const std::string& t) {
  const auto* b = reinterpret_cast<const unsigned char*>(t.data());
  const std::size_t n = t.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned c = b[i];
    std::size_t len = 0;
    unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (c < 0x80)
      len = 1;
    else if (c >= 0xC2 && c <= 0xDF)
      len = 2;
    else if (c >= 0xE0 && c <= 0xEF) {
      len = 3;
      if (c == 0xE0) lo = 0xA0;  // no overlong form
      if (c == 0xED) hi = 0x9F;  // no surrogate
    } else if (c >= 0xF0 && c <= 0xF4) {
      len = 4;
      if (c == 0xF0) lo = 0x90;
      if (c == 0xF4) hi = 0x8F;  // nothing above U+10FFFF
    } else {
      return i;
    }
    if (i + len > n) return i;
    for (std::size_t k = 1; k < len; k++) {
      const unsigned d = b[i + k];
      if (k == 1 ? (d < lo || d > hi) : (d < 0x80 || d > 0xBF)) return i;
    }
    i += len;
  }
  return std::string::npos;
}

void requireUtf8(const std::string& text, const std::string& what) {
  const std::size_t at = firstInvalidUtf8(text);
  if (at == std::string::npos) return;
  const auto line =
      1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n');
  throw ScenarioError(what + ": not valid UTF-8 at line " + std::to_string(line) + " (byte " +
                      std::to_string(at) + "); YAML text must be UTF-8");
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

std::vector<Part> actorBody(ActorClass cls, double height, const Material& material,
                            const Realism& realism) {
  std::vector<Part> parts;
  auto box = [&](double x, double y, double z, double sx, double sy, double sz) {
    Part p;
    p.kind = Part::Kind::Box;
    p.box = {{x, y, z}, {sx / 2, sy / 2, sz / 2}, 0.0};
    p.material = material;
    parts.push_back(p);
  };
  auto cyl = [&](double x, double y, double r, double z0, double z1, double albedo_scale,
                 double swing = 0) {
    Part p;
    p.kind = Part::Kind::Cylinder;
    p.cylinder = {{x, y}, r, z0, z1};
    p.material = material;
    p.material.albedo = std::clamp(material.albedo * albedo_scale, 0.02, 1.0);
    p.swing = swing;
    parts.push_back(p);
  };
  // Licence plates (520 x 110 mm, EU) front and back, retro-reflective.
  auto plates = [&](double half_length, double z) {
    if (!realism.retro_reflectors) return;
    for (const double x : {half_length + 0.01, -half_length - 0.01}) {
      Part p;
      p.kind = Part::Kind::Box;
      p.box = {{x, 0, z}, {0.01, 0.26, 0.055}, 0.0};
      p.material = Material{};
      p.material.albedo = 0.8;
      p.material.pattern = Pattern::Plain;
      p.material.retro = true;
      parts.push_back(p);
    }
  };
  const double s = height / 1.75;
  switch (cls) {
    case ActorClass::Pedestrian:  // legs, torso, head (different albedos: clothes vs skin)
      if (realism.gait) {  // each leg a thigh and a shin, swinging opposite; arms opposite legs
        for (const double side : {1.0, -1.0}) {
          cyl(0, 0.1 * side, 0.08 * s, 0.45 * s, 0.85 * s, 0.7, 0.12 * s * side);
          cyl(0, 0.1 * side, 0.07 * s, 0.0, 0.45 * s, 0.7, 0.3 * s * side);
          cyl(0, 0.26 * side * s, 0.045 * s, 0.8 * s, 1.45 * s, 1.0, -0.15 * s * side);
        }
      } else {
        cyl(0, 0.1, 0.08 * s, 0.0, 0.85 * s, 0.7);
        cyl(0, -0.1, 0.08 * s, 0.0, 0.85 * s, 0.7);
      }
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
      plates(2.2, 0.3 + 0.3 * s);
      break;
  }
  return parts;
}

Scenario Scenario::fromYamlText(const std::string& text, const std::string& share_dir,
                                const std::map<std::string, std::string>& overrides,
                                const std::string& source) {
  requireUtf8(text, source);
  for (const auto& [key, value] : overrides) requireUtf8(key + "=" + value, "override");
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
    detail::Loader(s, share_dir).load(detail::YamlView(&doc.node(), ""));
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
