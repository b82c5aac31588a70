// SPDX-License-Identifier: BSD-3-Clause
// MapPoint adapters over dynobj::io's PCD reader and writer; the PLY writer and reader.
#include "dynobj/mapclean/PointCloudIO.h"

#include <algorithm>
#include <fstream>
#include <sstream>
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

namespace {
constexpr std::size_t kCountField = 40;  // the count, "\ncomment" and padding
}  // namespace

PlyStreamWriter::PlyStreamWriter(const std::string& path) : file_(path) {
  file_.stream() << "ply\nformat binary_little_endian 1.0\ncomment mrpt-dynobj dynobj-mapclean\n"
                 << "element vertex ";
  count_pos_ = file_.stream().tellp();
  file_.stream() << std::string(kCountField, ' ')
                 << "\nproperty float x\nproperty float y\nproperty float z\n"
                 << "property float intensity\nend_header\n";
}

void PlyStreamWriter::add(const MapPoint& p) {
  const float v[4] = {p.x, p.y, p.z, p.intensity};
  file_.stream().write(reinterpret_cast<const char*>(v), sizeof(v));
  count_++;
}

void PlyStreamWriter::finish() {
  std::string field = std::to_string(count_) + "\ncomment";
  field.resize(kCountField, ' ');
  std::ofstream& out = file_.stream();
  const std::streampos end = out.tellp();
  out.seekp(count_pos_);
  out << field;
  out.seekp(end);
  out.flush();
  if (!out) throw std::runtime_error(io::cannotWriteMessage(file_.path()));
}

void PlyStreamWriter::commit() {
  finish();
  file_.commit();
}

void writePly(const std::string& path, const std::vector<MapPoint>& points) {
  PlyStreamWriter ply(path);
  for (const MapPoint& p : points) ply.add(p);
  ply.commit();
}

std::vector<MapPoint> readPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) io::throwFormatError(path, "cannot open it");
  std::string line;
  if (!std::getline(in, line) || line != "ply") io::throwFormatError(path, "not a PLY file");
  std::size_t count = 0;
  bool in_vertex = false, have_count = false;
  std::vector<std::string> props;
  for (;;) {
    if (!std::getline(in, line)) io::throwFormatError(path, "no end_header");
    std::istringstream ls(line);
    std::string word;
    ls >> word;
    if (word == "end_header") break;
    if (word == "format") {
      std::string f;
      ls >> f;
      if (f != "binary_little_endian")
        io::throwFormatError(path, "format " + f + ": only binary_little_endian is read");
    } else if (word == "element") {
      std::string name;
      ls >> name;
      in_vertex = name == "vertex";
      if (!in_vertex && have_count)  // elements after the vertices are not read
        continue;
      if (!in_vertex) io::throwFormatError(path, "element '" + name + "' before the vertices");
      ls >> count;
      have_count = true;
    } else if (word == "property" && in_vertex) {
      std::string type, name;
      ls >> type >> name;
      if (type != "float" && type != "float32")
        io::throwFormatError(path, "vertex property '" + name + "' is " + type + ", not float");
      props.push_back(name);
    }
  }
  const auto index = [&](const char* name) {
    const auto it = std::find(props.begin(), props.end(), name);
    return it == props.end() ? -1 : static_cast<int>(it - props.begin());
  };
  const int ix = index("x"), iy = index("y"), iz = index("z"), ii = index("intensity");
  if (!have_count || ix < 0 || iy < 0 || iz < 0)
    io::throwFormatError(path, "no vertex element with x, y, z");
  std::vector<MapPoint> points(count);
  std::vector<float> v(props.size());
  for (std::size_t k = 0; k < count; k++) {
    if (!in.read(reinterpret_cast<char*>(v.data()),
                 static_cast<std::streamsize>(v.size() * sizeof(float))))
      io::throwFormatError(
          path, "truncated: " + std::to_string(k) + " of " + std::to_string(count) + " vertices");
    points[k] = {v[ix], v[iy], v[iz], ii < 0 ? 0.f : v[ii]};
  }
  return points;
}

}  // namespace dynobj::mapclean
