// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/Texture.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dynobj::sim {
namespace {

/// Integer hash -> [0, 1).
double hash01(std::int64_t x, std::int64_t y, std::uint32_t seed) {
  std::uint64_t h =
      static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
      (static_cast<std::uint64_t>(y) + 0x632BE59BD9B4E019ULL) * 0xC2B2AE3D27D4EB4FULL ^
      seed * 0x165667B19E3779F9ULL;
  h ^= h >> 31;
  h *= 0xBF58476D1CE4E5B9ULL;
  h ^= h >> 29;
  return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0);
}

/// Bilinear value noise in [0, 1).
double valueNoise(double u, double v, std::uint32_t seed) {
  const double fu = std::floor(u), fv = std::floor(v);
  const auto iu = static_cast<std::int64_t>(fu), iv = static_cast<std::int64_t>(fv);
  const double a = u - fu, b = v - fv;
  const double sa = a * a * (3 - 2 * a), sb = b * b * (3 - 2 * b);
  const double n00 = hash01(iu, iv, seed), n10 = hash01(iu + 1, iv, seed);
  const double n01 = hash01(iu, iv + 1, seed), n11 = hash01(iu + 1, iv + 1, seed);
  return (n00 * (1 - sa) + n10 * sa) * (1 - sb) + (n01 * (1 - sa) + n11 * sa) * sb;
}

/// Posters: cells of 2*scale metres, most holding one rectangle of its own reflectivity.
double posters(const Eigen::Vector2d& uv, double scale, std::uint32_t seed) {
  const double cell = 2.0 * scale;
  const double cu = std::floor(uv.x() / cell), cv = std::floor(uv.y() / cell);
  const auto iu = static_cast<std::int64_t>(cu), iv = static_cast<std::int64_t>(cv);
  if (hash01(iu, iv, seed) < 0.25) return 0.5;  // empty wall here
  const double lu = uv.x() / cell - cu, lv = uv.y() / cell - cv;
  const double u0 = 0.1 + 0.3 * hash01(iu, iv, seed + 1),
               u1 = u0 + 0.3 + 0.25 * hash01(iu, iv, seed + 2);
  const double v0 = 0.1 + 0.3 * hash01(iu, iv, seed + 3),
               v1 = v0 + 0.3 + 0.25 * hash01(iu, iv, seed + 4);
  if (lu < u0 || lu > u1 || lv < v0 || lv > v1) return 0.5;
  const double inner = hash01(iu, iv, seed + 5) < 0.5 ? 0.05 : 0.95;
  // Some posters carry a stripe of text-like blocks: corners for ORB.
  const double text =
      valueNoise(uv.x() * 8 / scale, uv.y() * 8 / scale, seed + 6) > 0.55 ? 0.3 : 0.0;
  return std::clamp(inner - (inner > 0.5 ? text : -text), 0.0, 1.0);
}

/// Floor markings: lanes every 3*scale metres plus a sparse grid of tiles.
double markings(const Eigen::Vector2d& uv, double scale, std::uint32_t seed) {
  const double lane = 3.0 * scale, width = 0.12;
  const double mu = std::fmod(std::abs(uv.x()), lane), mv = std::fmod(std::abs(uv.y()), lane);
  if (mu < width || mv < width) return 0.95;
  const double tile = std::floor(uv.x() / scale) + 7 * std::floor(uv.y() / scale);
  return hash01(static_cast<std::int64_t>(tile), 0, seed) < 0.1 ? 0.8 : 0.45;
}

}  // namespace

Pattern patternFromString(const std::string& name) {
  if (name == "plain") return Pattern::Plain;
  if (name == "noise") return Pattern::Noise;
  if (name == "stripes") return Pattern::Stripes;
  if (name == "checker") return Pattern::Checker;
  if (name == "posters") return Pattern::Posters;
  if (name == "markings") return Pattern::Markings;
  throw std::invalid_argument("unknown texture pattern '" + name +
                              "' (plain, noise, stripes, checker, posters, markings)");
}

double reflectivity(const Material& m, const Eigen::Vector2d& uv) {
  const double s = std::max(m.scale, 1e-3);
  double p = 0.5;  // pattern value in [0, 1], 0.5 = albedo
  switch (m.pattern) {
    case Pattern::Plain:
      break;
    case Pattern::Noise:
      p = 0.65 * valueNoise(uv.x() / s, uv.y() / s, m.seed) +
          0.35 * valueNoise(uv.x() * 4 / s, uv.y() * 4 / s, m.seed + 9);
      break;
    case Pattern::Stripes:
      p = std::fmod(std::abs(uv.x()) / s, 1.0) < 0.5 ? 0.1 : 0.9;
      break;
    case Pattern::Checker:
      p = (static_cast<std::int64_t>(std::floor(uv.x() / s) + std::floor(uv.y() / s)) & 1) ? 0.15
                                                                                           : 0.85;
      break;
    case Pattern::Posters:
      p = posters(uv, s, m.seed);
      break;
    case Pattern::Markings:
      p = markings(uv, s, m.seed);
      break;
  }
  // Fine grain on every surface (paint, dirt): real signal images are never flat.
  const double grain = valueNoise(uv.x() * 20, uv.y() * 20, m.seed + 77) - 0.5;
  const double r = m.albedo * (1.0 + 2.0 * m.contrast * (p - 0.5)) + 0.05 * grain;
  return std::clamp(r, 0.02, 1.0);
}

}  // namespace dynobj::sim
