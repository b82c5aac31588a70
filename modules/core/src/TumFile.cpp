// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/TumFile.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace dynobj::core {

std::vector<StampedPose> readTumFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open TUM file '" + path + "'");
  std::vector<StampedPose> out;
  std::string line;
  std::size_t n = 0;
  while (std::getline(in, line)) {
    n++;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string ts;
    double x, y, z, qx, qy, qz, qw;
    if (!(ss >> ts >> x >> y >> z >> qx >> qy >> qz >> qw))
      throw std::runtime_error(path + ":" + std::to_string(n) +
                               ": expected 'timestamp tx ty tz qx qy qz qw'");
    // Seconds with a fractional part, parsed exactly into nanoseconds.
    const auto dot = ts.find('.');
    std::int64_t sec = 0, frac = 0;
    try {
      sec = std::stoll(ts.substr(0, dot));
      if (dot != std::string::npos) {
        std::string f = ts.substr(dot + 1);
        f.resize(9, '0');
        frac = std::stoll(f.substr(0, 9));
      }
    } catch (const std::exception&) {
      throw std::runtime_error(path + ":" + std::to_string(n) + ": bad timestamp '" + ts + "'");
    }
    const Eigen::Quaterniond q(qw, qx, qy, qz);
    if (std::abs(q.norm() - 1.0) > 1e-3)
      throw std::runtime_error(path + ":" + std::to_string(n) + ": quaternion is not unit length");
    StampedPose p;
    p.timestamp_ns = sec * 1000000000 + frac;
    p.pose.linear() = q.normalized().toRotationMatrix();
    p.pose.translation() = Eigen::Vector3d(x, y, z);
    out.push_back(p);
  }
  return out;
}

const StampedPose* findPose(const std::vector<StampedPose>& poses, std::int64_t t,
                            std::int64_t tolerance_ns) {
  const auto it =
      std::lower_bound(poses.begin(), poses.end(), t,
                       [](const StampedPose& p, std::int64_t v) { return p.timestamp_ns < v; });
  const StampedPose* best = nullptr;
  std::int64_t best_d = tolerance_ns + 1;
  for (auto c : {it, it == poses.begin() ? it : it - 1})
    if (c != poses.end() && std::llabs(c->timestamp_ns - t) < best_d) {
      best = &*c;
      best_d = std::llabs(c->timestamp_ns - t);
    }
  return best;
}

}  // namespace dynobj::core
