// SPDX-License-Identifier: BSD-3-Clause
// Procedural surface reflectivity, so that simulated intensity images have the edges and corners
// (posters, floor markings, stripes, grain) that ORB needs, like real Ouster signal images.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>

namespace dynobj::sim {

enum class Pattern { Plain, Noise, Stripes, Checker, Posters, Markings };

/// Parses "plain", "noise", "stripes", "checker", "posters", "markings"; throws
/// std::invalid_argument listing the valid names.
Pattern patternFromString(const std::string& name);

struct Material {
  double albedo = 0.3;  ///< mean reflectivity, 0..1
  Pattern pattern = Pattern::Noise;
  double scale = 1.0;      ///< pattern feature size [m]
  double contrast = 0.6;   ///< 0 = flat, 1 = full swing around albedo
  std::uint32_t seed = 1;  ///< varies the pattern between surfaces
  bool retro = false;      ///< a retro-reflector: kRetroGain times the reflectivity
};

/// How much brighter a retro-reflector returns than a white diffuse surface (Velodyne reports
/// retro-reflectors above 100, diffuse surfaces 0-100: this saturates its 255).
constexpr double kRetroGain = 10.0;

/// Reflectivity in [0.02, 1] at surface coordinates `uv` [m]. Deterministic.
double reflectivity(const Material& m, const Eigen::Vector2d& uv);

}  // namespace dynobj::sim
