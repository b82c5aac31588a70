// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/PointCloudIO.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

namespace dynobj::mapclean {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw PointCloudFileError(path + ": " + what);
}

/// One PCD field: byte offset in a binary record, size, type letter, element count.
struct Field {
  std::string name;
  std::size_t size = 4, count = 1, offset = 0;
  char type = 'F';
};

double readScalar(const char* p, const Field& f) {
  auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof(v));
    return static_cast<double>(v);
  };
  if (f.type == 'F') return f.size == 8 ? get(double{}) : get(float{});
  if (f.type == 'U')
    return f.size == 1   ? get(std::uint8_t{})
           : f.size == 2 ? get(std::uint16_t{})
           : f.size == 4 ? get(std::uint32_t{})
                         : get(std::uint64_t{});
  return f.size == 1   ? get(std::int8_t{})
         : f.size == 2 ? get(std::int16_t{})
         : f.size == 4 ? get(std::int32_t{})
                       : get(std::int64_t{});
}

std::string viewpointLine(const Eigen::Isometry3d& vp) {
  const Eigen::Quaterniond q(vp.linear());
  std::ostringstream s;
  s << std::setprecision(9) << "VIEWPOINT " << vp.translation().x() << " " << vp.translation().y()
    << " " << vp.translation().z() << " " << q.w() << " " << q.x() << " " << q.y() << " " << q.z();
  return s.str();
}

constexpr const char* kFieldsHeader =
    "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\nFIELDS x y z intensity\n"
    "SIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n";
constexpr int kCountWidth = 12;  // the streamed header reserves this many characters per count

void writeRecord(std::ostream& out, const MapPoint& p) {
  const float v[4] = {p.x, p.y, p.z, p.intensity};
  out.write(reinterpret_cast<const char*>(v), sizeof(v));
}

}  // namespace

PcdCloud readPcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, "cannot open PCD file");
  std::vector<Field> fields;
  std::size_t points = 0, line_no = 0;
  std::string data;
  PcdCloud cloud;
  std::vector<std::size_t> sizes, counts;
  std::vector<char> types;
  for (std::string line; data.empty() && std::getline(in, line);) {
    line_no++;
    if (line.empty()) continue;
    if (line[0] == '#') {
      const auto start = line.find_first_not_of("# ");
      if (line_no > 1 && start != std::string::npos) cloud.comments.push_back(line.substr(start));
      continue;
    }
    std::istringstream ss(line);
    std::string key;
    ss >> key;
    const std::string where = "line " + std::to_string(line_no) + ": ";
    if (key == "FIELDS") {
      for (std::string n; ss >> n;) fields.push_back({n});
    } else if (key == "SIZE") {
      for (std::size_t v; ss >> v;) sizes.push_back(v);
    } else if (key == "TYPE") {
      for (char c; ss >> c;) types.push_back(c);
    } else if (key == "COUNT") {
      for (std::size_t v; ss >> v;) counts.push_back(v);
    } else if (key == "POINTS") {
      if (!(ss >> points)) fail(path, where + "bad POINTS");
    } else if (key == "VIEWPOINT") {
      double t[3], q[4];
      if (!(ss >> t[0] >> t[1] >> t[2] >> q[0] >> q[1] >> q[2] >> q[3]))
        fail(path, where + "VIEWPOINT needs 'tx ty tz qw qx qy qz'");
      const Eigen::Quaterniond quat(q[0], q[1], q[2], q[3]);
      if (std::abs(quat.norm() - 1.0) > 1e-3)
        fail(path, where + "VIEWPOINT quaternion is not unit length");
      cloud.viewpoint.linear() = quat.normalized().toRotationMatrix();
      cloud.viewpoint.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
    } else if (key == "DATA") {
      ss >> data;
    } else if (key != "VERSION" && key != "WIDTH" && key != "HEIGHT") {
      fail(path, where + "not a PCD header line: '" + line.substr(0, 40) + "'");
    }
  }
  if (data.empty()) fail(path, "not a PCD file (no DATA line)");
  if (data != "binary" && data != "ascii")
    fail(path, "unsupported DATA " + data + " (ascii or binary only)");
  if (sizes.size() != fields.size() || types.size() != fields.size())
    fail(path, "FIELDS, SIZE and TYPE have different lengths");
  std::map<std::string, std::size_t> index;
  std::size_t record = 0, values = 0;
  for (std::size_t i = 0; i < fields.size(); i++) {
    Field& f = fields[i];
    f.size = sizes[i];
    f.type = types[i];
    f.count = i < counts.size() ? counts[i] : 1;
    if (f.size != 1 && f.size != 2 && f.size != 4 && f.size != 8)
      fail(path, "bad SIZE of field " + f.name);
    if (f.type != 'F' && f.type != 'U' && f.type != 'I') fail(path, "bad TYPE of field " + f.name);
    f.offset = record;
    record += f.size * f.count;
    index[f.name] = values;
    values += f.count;
  }
  for (const char* n : {"x", "y", "z"})
    if (!index.count(n)) fail(path, std::string("no field '") + n + "'");
  cloud.has_intensity = index.count("intensity") > 0;
  const auto fi = [&](const char* n) {
    for (const Field& f : fields)
      if (f.name == n) return f;
    return Field{};
  };
  const Field fx = fi("x"), fy = fi("y"), fz = fi("z"), fint = fi("intensity");
  cloud.points.resize(points);
  if (data == "binary") {
    std::vector<char> buf(record * points);
    if (!in.read(buf.data(), static_cast<std::streamsize>(buf.size())))
      fail(path, "is truncated: expected " + std::to_string(points) + " points");
    for (std::size_t i = 0; i < points; i++) {
      const char* r = buf.data() + i * record;
      MapPoint& p = cloud.points[i];
      p.x = static_cast<float>(readScalar(r + fx.offset, fx));
      p.y = static_cast<float>(readScalar(r + fy.offset, fy));
      p.z = static_cast<float>(readScalar(r + fz.offset, fz));
      if (cloud.has_intensity) p.intensity = static_cast<float>(readScalar(r + fint.offset, fint));
    }
  } else {
    std::vector<double> v(values);
    for (std::size_t i = 0; i < points; i++) {
      for (double& x : v)
        if (!(in >> x)) fail(path, "is truncated or malformed at point " + std::to_string(i));
      cloud.points[i] = {static_cast<float>(v[index["x"]]), static_cast<float>(v[index["y"]]),
                         static_cast<float>(v[index["z"]]),
                         cloud.has_intensity ? static_cast<float>(v[index["intensity"]]) : 0.f};
    }
  }
  return cloud;
}

void writePcd(const std::string& path, const std::vector<MapPoint>& points,
              const Eigen::Isometry3d& viewpoint, const std::string& comment) {
  core::AtomicFile f(path);
  f.stream() << kFieldsHeader << (comment.empty() ? "" : "# " + comment + "\n") << "WIDTH "
             << points.size() << "\nHEIGHT 1\n"
             << viewpointLine(viewpoint) << "\nPOINTS " << points.size() << "\nDATA binary\n";
  for (const MapPoint& p : points) writeRecord(f.stream(), p);
  f.commit();
}

PcdStreamWriter::PcdStreamWriter(const std::string& path, const Eigen::Isometry3d& viewpoint)
    : file_(path) {
  auto& o = file_.stream();
  o << kFieldsHeader << "WIDTH ";
  width_pos_ = o.tellp();
  o << std::string(kCountWidth, ' ') << "\nHEIGHT 1\n" << viewpointLine(viewpoint) << "\nPOINTS ";
  points_pos_ = o.tellp();
  o << std::string(kCountWidth, ' ') << "\nDATA binary\n";
}

void PcdStreamWriter::add(const MapPoint& p) {
  writeRecord(file_.stream(), p);
  count_++;
}

void PcdStreamWriter::close() {
  auto& o = file_.stream();
  const auto end = o.tellp();
  const std::string n = std::to_string(count_);  // left-aligned; trailing blanks are separators
  for (auto pos : {width_pos_, points_pos_}) {
    o.seekp(pos);
    o << n;
  }
  o.seekp(end);
  file_.commit();
}

void writePly(const std::string& path, const std::vector<MapPoint>& points) {
  core::AtomicFile f(path);
  f.stream() << "ply\nformat binary_little_endian 1.0\ncomment mrpt-dynobj dynobj-mapclean\n"
             << "element vertex " << points.size()
             << "\nproperty float x\nproperty float y\nproperty float z\nproperty float intensity\n"
             << "end_header\n";
  for (const MapPoint& p : points) writeRecord(f.stream(), p);
  f.commit();
}

}  // namespace dynobj::mapclean
