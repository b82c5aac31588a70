// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/eval/DriftModel.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace dynobj::eval {

DriftParams DriftParams::parse(const std::string& text) {
  DriftParams p;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (item.empty()) continue;
    const auto eq = item.find('=');
    if (eq == std::string::npos)
      throw std::invalid_argument("drift: '" + item + "' is not key=value");
    const std::string key = item.substr(0, eq), value = item.substr(eq + 1);
    double v = 0;
    try {
      std::size_t used = 0;
      v = std::stod(value, &used);
      if (used != value.size()) throw std::invalid_argument(value);
    } catch (const std::exception&) {
      throw std::invalid_argument("drift: " + key + ": '" + value + "' is not a number");
    }
    if (key == "sigma_xy")
      p.sigma_xy = v;
    else if (key == "sigma_yaw_deg")
      p.sigma_yaw_deg = v;
    else if (key == "bias_scale")
      p.bias_scale = v;
    else if (key == "bias_yaw_deg")
      p.bias_yaw_deg = v;
    else if (key == "seed")
      p.seed = static_cast<int>(v);
    else
      throw std::invalid_argument("drift: unknown key '" + key +
                                  "' (sigma_xy, sigma_yaw_deg, bias_scale, bias_yaw_deg, seed)");
  }
  if (p.sigma_xy < 0 || p.sigma_yaw_deg < 0)
    throw std::invalid_argument("drift: sigmas must be >= 0");
  return p;
}

std::string DriftParams::toString() const {
  std::ostringstream ss;
  ss << "sigma_xy=" << sigma_xy << " m, sigma_yaw=" << sigma_yaw_deg << " deg, scale bias "
     << bias_scale * 100 << " %, yaw bias " << bias_yaw_deg << " deg/frame";
  return ss.str();
}

DriftModel::DriftModel(const DriftParams& p) : p_(p), rng_(static_cast<unsigned>(p.seed)) {}

Eigen::Isometry3d DriftModel::corrupt(const Eigen::Isometry3d& motion) {
  std::normal_distribution<double> g(0.0, 1.0);
  const double yaw = (p_.bias_yaw_deg + p_.sigma_yaw_deg * g(rng_)) * M_PI / 180.0;
  Eigen::Isometry3d out = motion;
  out.translation() = motion.translation() * (1.0 + p_.bias_scale) +
                      Eigen::Vector3d(p_.sigma_xy * g(rng_), p_.sigma_xy * g(rng_), 0.0);
  out.linear() =
      Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * motion.linear();
  return out;
}

}  // namespace dynobj::eval
