// SPDX-License-Identifier: BSD-3-Clause
// MapPoint adapters over dynobj::io's PCD reader and writer, and the PLY writer.
#include "dynobj/mapclean/PointCloudIO.h"

#include <utility>

namespace dynobj::mapclean {

PcdCloud readPcd(const std::string& path) {
  io::CloudFile file = io::readPcd(path);
  const core::PointCloud& c = file.cloud;
  PcdCloud cloud;
  cloud.viewpoint = file.viewpoint;
  cloud.has_intensity = c.hasIntensity();
  cloud.comments = std::move(file.comments);
  cloud.points.resize(c.size());
  for (std::size_t i = 0; i < c.size(); i++)
    cloud.points[i] = {c.x[i], c.y[i], c.z[i], cloud.has_intensity ? c.intensity[i] : 0.f};
  return cloud;
}

void writePcd(const std::string& path, const std::vector<MapPoint>& points,
              const Eigen::Isometry3d& viewpoint, const std::string& comment) {
  io::PcdWriter w(path, viewpoint, comment, points.size());
  for (const MapPoint& p : points) w.add(p.x, p.y, p.z, p.intensity);
  w.close();
}

PcdStreamWriter::PcdStreamWriter(const std::string& path, const Eigen::Isometry3d& viewpoint)
    : writer_(path, viewpoint) {}

void PcdStreamWriter::add(const MapPoint& p) {
  writer_.add(p.x, p.y, p.z, p.intensity);
}

void PcdStreamWriter::close() {
  writer_.close();
}

void writePly(const std::string& path, const std::vector<MapPoint>& points) {
  io::AtomicFile f(path);
  f.stream() << "ply\nformat binary_little_endian 1.0\ncomment mrpt-dynobj dynobj-mapclean\n"
             << "element vertex " << points.size()
             << "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\n"
             << "end_header\n";
  for (const MapPoint& p : points) {
    const float v[4] = {p.x, p.y, p.z, p.intensity};
    f.stream().write(reinterpret_cast<const char*>(v), sizeof(v));
  }
  f.commit();
}

}  // namespace dynobj::mapclean
