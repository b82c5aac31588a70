// SPDX-License-Identifier: BSD-3-Clause
// readPoseFile: KITTI 3x4 and TUM trajectories, told apart by their column count.
#include "dynobj/io/PoseFile.h"

#include <Eigen/LU>
#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace dynobj::io {
namespace {

[[noreturn]] void failAt(const std::string& path, std::size_t line, const std::string& problem) {
  throwFormatError(path + ":" + std::to_string(line), problem);
}

double toNumber(const std::string& path, std::size_t line, const std::string& tok) {
  double v = 0;
  const char* b = tok.data() + (tok[0] == '+');
  const auto r = std::from_chars(b, tok.data() + tok.size(), v);
  if (r.ec != std::errc() || r.ptr != tok.data() + tok.size())
    failAt(path, line, "'" + tok + "' is not a number");
  if (!std::isfinite(v)) failAt(path, line, "'" + tok + "' is not finite");
  return v;
}

}  // namespace

std::optional<std::int64_t> parseSecondsNs(const std::string& text) {
  const std::size_t neg = !text.empty() && text[0] == '-';
  const std::string s = text.substr(neg);
  const auto dot = s.find('.');
  const std::string whole = s.substr(0, dot),
                    frac = dot == std::string::npos ? "" : s.substr(dot + 1);
  const auto digits = [](const std::string& d) {
    return d.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!s.empty() && s != "." && digits(whole) && digits(frac) && whole.size() <= 10) {
    std::int64_t sec = 0, ns = 0;
    std::from_chars(whole.data(), whole.data() + whole.size(), sec);
    if (sec > 9000000000) return std::nullopt;  // beyond int64 nanoseconds
    std::string f = frac.substr(0, 9);
    f.resize(9, '0');
    std::from_chars(f.data(), f.data() + 9, ns);
    return (neg ? -1 : 1) * (sec * 1000000000 + ns);
  }
  double v = 0;
  const auto r = std::from_chars(text.data(), text.data() + text.size(), v);
  if (r.ec != std::errc() || r.ptr != text.data() + text.size() || !(std::abs(v) < 9e9))
    return std::nullopt;
  return std::llround(v * 1e9);
}

std::vector<TimedPose> readPoseFile(const std::string& path, PoseFormat format) {
  std::ifstream in(path);
  if (!in) throwFormatError(path, "cannot open pose file");
  std::vector<TimedPose> out;
  std::size_t line_no = 0;
  for (std::string line; std::getline(in, line);) {
    line_no++;
    std::istringstream ss(line.substr(0, line.find('#')));
    std::vector<std::string> tok;
    for (std::string t; ss >> t;) tok.push_back(t);
    if (tok.empty()) continue;
    if (format == PoseFormat::Auto) {
      if (tok.size() != 12 && tok.size() != 8)
        failAt(path, line_no,
               "expected 12 numbers (KITTI 3x4) or 8 (TUM: t tx ty tz qx qy qz qw)"
               ", found " +
                   std::to_string(tok.size()));
      format = tok.size() == 12 ? PoseFormat::Kitti : PoseFormat::Tum;
    }
    const std::size_t want = format == PoseFormat::Kitti ? 12 : 8;
    if (tok.size() != want)
      failAt(path, line_no,
             "expected " + std::to_string(want) + " numbers (" +
                 (want == 12 ? "KITTI 3x4" : "TUM") + " file), found " +
                 std::to_string(tok.size()));
    TimedPose p;
    if (format == PoseFormat::Kitti) {
      Eigen::Matrix<double, 3, 4> m;
      for (int k = 0; k < 12; k++) m(k / 4, k % 4) = toNumber(path, line_no, tok[k]);
      const Eigen::Matrix3d r = m.leftCols<3>();
      const double err = (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      if (!(err <= 1e-3) || r.determinant() < 0)
        failAt(path, line_no,
               "the 3x3 part is not a rotation (max |R'R - I| = " + std::to_string(err) +
                   ", det = " + std::to_string(r.determinant()) + ")");
      p.pose.linear() = Eigen::Quaterniond(r).normalized().toRotationMatrix();
      p.pose.translation() = m.col(3);
    } else {
      const auto t = parseSecondsNs(tok[0]);
      if (!t) failAt(path, line_no, "'" + tok[0] + "' is not a time stamp in seconds");
      double v[7];
      for (int k = 0; k < 7; k++) v[k] = toNumber(path, line_no, tok[k + 1]);
      const Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
      if (!(std::abs(q.norm() - 1.0) <= 1e-3))
        failAt(path, line_no,
               "quaternion is not unit length (|q| = " + std::to_string(q.norm()) + ")");
      if (!out.empty() && *t <= out.back().timestamp_ns)
        failAt(path, line_no, "time stamp " + tok[0] + " is not after the previous pose's");
      p.timestamp_ns = *t;
      p.pose.linear() = q.normalized().toRotationMatrix();
      p.pose.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
    }
    out.push_back(p);
  }
  if (out.empty()) throwFormatError(path, "holds no pose");
  return out;
}

const TimedPose* findPose(const std::vector<TimedPose>& poses, std::int64_t t,
                          std::int64_t tolerance_ns) {
  const auto it =
      std::lower_bound(poses.begin(), poses.end(), t,
                       [](const TimedPose& p, std::int64_t v) { return p.timestamp_ns < v; });
  const TimedPose* best = nullptr;
  std::int64_t best_d = tolerance_ns + 1;
  for (auto c : {it, it == poses.begin() ? it : it - 1})
    if (c != poses.end() && std::llabs(c->timestamp_ns - t) < best_d) {
      best = &*c;
      best_d = std::llabs(c->timestamp_ns - t);
    }
  return best;
}

TumWriter::TumWriter(const std::string& path, const std::string& note) : file_(path) {
  file_.stream() << "# timestamp tx ty tz qx qy qz qw  (" << note << ")\n";
}

void TumWriter::write(std::int64_t timestamp_ns, const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q(pose.linear());
  const Eigen::Vector3d& t = pose.translation();
  file_.stream() << timestamp_ns / 1000000000 << "." << std::setw(9) << std::setfill('0')
                 << timestamp_ns % 1000000000 << std::setfill(' ') << std::fixed
                 << std::setprecision(6) << " " << t.x() << " " << t.y() << " " << t.z() << " "
                 << q.x() << " " << q.y() << " " << q.z() << " " << q.w() << "\n";
}

}  // namespace dynobj::io
