// SPDX-License-Identifier: BSD-3-Clause
// PcdWriter / writePcd: binary PCD v0.7, fields x y z intensity (float32), written atomically.
#include <iomanip>
#include <sstream>

#include "dynobj/io/PcdFile.h"

namespace dynobj::io {
namespace {

constexpr const char* kFieldsHeader =
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\n"
    "SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n";
constexpr int kCountWidth = 12;  // an unknown count reserves this many characters

std::string viewpointLine(const Eigen::Isometry3d& vp) {
  const Eigen::Quaterniond q(vp.linear());
  std::ostringstream s;
  s << std::setprecision(9) << "VIEWPOINT " << vp.translation().x() << " " << vp.translation().y()
    << " " << vp.translation().z() << " " << q.w() << " " << q.x() << " " << q.y() << " " << q.z();
  return s.str();
}

}  // namespace

PcdWriter::PcdWriter(const std::string& path, const Eigen::Isometry3d& viewpoint,
                     const std::string& comment, std::optional<std::size_t> points)
    : file_(path), announced_(points) {
  const std::string count = points ? std::to_string(*points) : std::string(kCountWidth, ' ');
  auto& o = file_.stream();
  o << kFieldsHeader << (comment.empty() ? "" : "# " + comment + "\n") << "WIDTH ";
  width_pos_ = o.tellp();
  o << count << "\nHEIGHT 1\n" << viewpointLine(viewpoint) << "\nPOINTS ";
  points_pos_ = o.tellp();
  o << count << "\nDATA binary\n";
}

void PcdWriter::add(float x, float y, float z, float intensity) {
  const float v[4] = {x, y, z, intensity};
  file_.stream().write(reinterpret_cast<const char*>(v), sizeof(v));
  count_++;
}

void PcdWriter::close() {
  if (announced_) {
    if (*announced_ != count_)
      throwFormatError(file_.path(), "PcdWriter: " + std::to_string(count_) + " points added, " +
                                         std::to_string(*announced_) + " announced");
  } else {
    auto& o = file_.stream();
    const auto end = o.tellp();
    const std::string n = std::to_string(count_);  // left-aligned; trailing blanks separate
    for (const auto pos : {width_pos_, points_pos_}) {
      o.seekp(pos);
      o << n;
    }
    o.seekp(end);
  }
  file_.commit();
}

void writePcd(const std::string& path, const core::PointCloud& cloud,
              const Eigen::Isometry3d& viewpoint, const std::string& comment) {
  cloud.validate();
  PcdWriter w(path, viewpoint, comment, cloud.size());
  for (std::size_t i = 0; i < cloud.size(); i++)
    w.add(cloud.x[i], cloud.y[i], cloud.z[i], cloud.hasIntensity() ? cloud.intensity[i] : 0.f);
  w.close();
}

}  // namespace dynobj::io
