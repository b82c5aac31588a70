// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/SensorModel.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "dynobj/core/Config.h"

namespace dynobj::core {
namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

/// Half of the gap between the two extreme beams at one end of a sorted (descending) table.
double halfGap(const std::vector<double>& sorted_desc, bool top) {
  if (sorted_desc.size() < 2) return 0.5 * M_PI / 180.0;
  const std::size_t n = sorted_desc.size();
  return top ? 0.5 * (sorted_desc[0] - sorted_desc[1])
             : 0.5 * (sorted_desc[n - 2] - sorted_desc[n - 1]);
}

}  // namespace

void SensorModel::loadFromConfigFile(const ::mrpt::config::CConfigFileBase& c,
                                     const std::string& s) {
  model = readString(c, s, "model", model);
  rows = readInt(c, s, "rows", rows, true);
  cols = readInt(c, s, "cols", cols, true);
  beam_elevations = readDoubleList(c, s, "beam_elevations");
  for (double& e : beam_elevations) e /= kRadToDeg;
  const bool has_table = !beam_elevations.empty();
  elevation_top = readDegrees(c, s, "elevation_top", elevation_top, !has_table);
  elevation_bottom = readDegrees(c, s, "elevation_bottom", elevation_bottom, !has_table);
  min_range = readDouble(c, s, "min_range", min_range);
  max_range = readDouble(c, s, "max_range", max_range);
  frequency = readDouble(c, s, "frequency", frequency);
  validate();
}

const std::vector<std::string>& SensorModel::iniKeys() {
  static const std::vector<std::string> keys{"model",           "rows",          "cols",
                                             "beam_elevations", "elevation_top", "elevation_bottom",
                                             "min_range",       "max_range",     "frequency"};
  return keys;
}

void SensorModel::saveToConfigFile(::mrpt::config::CConfigFileBase& c, const std::string& s) const {
  c.write(s, "model", model);
  c.write(s, "rows", rows);
  c.write(s, "cols", cols);
  c.write(s, "elevation_top", elevation_top * kRadToDeg);
  c.write(s, "elevation_bottom", elevation_bottom * kRadToDeg);
  if (!beam_elevations.empty()) {
    std::ostringstream ss;
    for (std::size_t i = 0; i < beam_elevations.size(); i++)
      ss << (i ? " " : "") << beam_elevations[i] * kRadToDeg;
    c.write(s, "beam_elevations", ss.str());
  }
  c.write(s, "min_range", min_range);
  c.write(s, "max_range", max_range);
  c.write(s, "frequency", frequency);
}

void SensorModel::validate() const {
  requireInRange("rows", rows, 1, 4096);
  requireInRange("cols", cols, 8, 65535);
  requirePositive("min_range", min_range + 1e-12);
  requirePositive("max_range", max_range);
  if (max_range <= min_range) throwParameterError("max_range", "must be greater than min_range");
  requirePositive("frequency", frequency);
  const double half_pi = M_PI / 2;
  if (isUniform()) {
    requireInRange("elevation_top", elevation_top, -half_pi, half_pi);
    requireInRange("elevation_bottom", elevation_bottom, -half_pi, half_pi);
    if (rows > 1 && !(elevation_top > elevation_bottom))
      throwParameterError("elevation_top", "must be above elevation_bottom");
  } else {
    if (static_cast<int>(beam_elevations.size()) != rows) {
      std::ostringstream ss;
      ss << "has " << beam_elevations.size() << " entries but rows = " << rows;
      throwParameterError("beam_elevations", ss.str());
    }
    for (double e : beam_elevations) requireInRange("beam_elevations", e, -half_pi, half_pi);
    auto sorted = rowElevations();
    for (std::size_t i = 1; i < sorted.size(); i++)
      if (sorted[i] == sorted[i - 1])
        throwParameterError("beam_elevations", "two beams share the same elevation");
  }
}

std::vector<double> SensorModel::rowElevations() const {
  std::vector<double> out;
  if (isUniform()) {
    out.resize(static_cast<std::size_t>(std::max(rows, 0)));
    const double step = rows > 1 ? (elevation_top - elevation_bottom) / (rows - 1) : 0.0;
    for (int r = 0; r < rows; r++) out[static_cast<std::size_t>(r)] = elevation_top - r * step;
    return out;
  }
  out = beam_elevations;
  std::sort(out.begin(), out.end(), std::greater<>());
  return out;
}

std::vector<int> SensorModel::laserToRow() const {
  std::vector<int> out(static_cast<std::size_t>(std::max(rows, 0)));
  std::iota(out.begin(), out.end(), 0);
  if (isUniform()) return out;
  std::vector<int> order(beam_elevations.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return beam_elevations[static_cast<std::size_t>(a)] >
           beam_elevations[static_cast<std::size_t>(b)];
  });
  for (std::size_t row = 0; row < order.size(); row++)
    out[static_cast<std::size_t>(order[row])] = static_cast<int>(row);
  return out;
}

double SensorModel::fovUp() const {
  const auto e = rowElevations();
  if (e.empty()) return 0;
  return e.front() + halfGap(e, true);
}

double SensorModel::fovSpan() const {
  const auto e = rowElevations();
  if (e.empty()) return 0;
  return fovUp() - (e.back() - halfGap(e, false));
}

}  // namespace dynobj::core
