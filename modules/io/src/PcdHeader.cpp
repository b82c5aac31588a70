// SPDX-License-Identifier: BSD-3-Clause
// The PCD header: one keyword per line (VERSION FIELDS SIZE TYPE COUNT WIDTH HEIGHT VIEWPOINT
// POINTS, '#' comments), closed by the DATA line; the data starts at the next byte.
#include "PcdHeader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <sstream>

#include "dynobj/io/FormatError.h"

namespace dynobj::io::detail {
namespace {

std::size_t toCount(const std::string& path, std::size_t line, const std::string& key,
                    const std::string& tok) {
  std::size_t v = 0;
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (r.ec != std::errc() || r.ptr != tok.data() + tok.size())
    failAt(path, line, "bad " + key + " value '" + tok + "'");
  return v;
}

bool supported(char type, std::size_t size) {
  if (type == 'F') return size == 4 || size == 8;
  return (type == 'U' || type == 'I') && (size == 1 || size == 2 || size == 4 || size == 8);
}

}  // namespace

void failAt(const std::string& path, std::size_t line, const std::string& problem) {
  throwFormatError(path + ":" + std::to_string(line), problem);
}

PcdHeader parsePcdHeader(const std::string& path, const std::string& buf, CloudFile& out) {
  PcdHeader h;
  std::vector<std::size_t> sizes, counts;
  std::vector<std::string> types;
  std::optional<std::size_t> width, height, points;
  std::size_t pos = 0, line_no = 0;
  while (h.data.empty() && pos < buf.size()) {
    const std::size_t nl = std::min(buf.find('\n', pos), buf.size());
    std::string line = buf.substr(pos, nl - pos);
    pos = nl + 1;
    line_no++;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (!line.empty() && line[0] == '#') {  // the ".PCD v0.7 - ..." banner is not kept
      const auto start = line.find_first_not_of("# ");
      if (start != std::string::npos && line.compare(start, 5, ".PCD ") != 0)
        out.comments.push_back(line.substr(start));
      continue;
    }
    std::istringstream ss(line.substr(0, line.find('#')));
    std::string key, tok;
    if (!(ss >> key)) continue;
    if (key == "FIELDS" || key == "COLUMNS") {  // COLUMNS: the v0.5 name
      while (ss >> tok) h.fields.push_back({tok});
    } else if (key == "SIZE" || key == "COUNT") {
      while (ss >> tok)
        (key == "SIZE" ? sizes : counts).push_back(toCount(path, line_no, key, tok));
    } else if (key == "TYPE") {
      while (ss >> tok) types.push_back(tok);
    } else if (key == "WIDTH" || key == "HEIGHT" || key == "POINTS") {
      if (!(ss >> tok)) failAt(path, line_no, key + " without a value");
      (key == "WIDTH"    ? width
       : key == "HEIGHT" ? height
                         : points) = toCount(path, line_no, key, tok);
    } else if (key == "VIEWPOINT") {
      double t[3], q[4];
      if (!(ss >> t[0] >> t[1] >> t[2] >> q[0] >> q[1] >> q[2] >> q[3]))
        failAt(path, line_no, "VIEWPOINT needs 'tx ty tz qw qx qy qz'");
      const Eigen::Quaterniond quat(q[0], q[1], q[2], q[3]);
      if (!(std::abs(quat.norm() - 1.0) <= 1e-3))
        failAt(path, line_no, "VIEWPOINT quaternion is not unit length");
      out.viewpoint.linear() = quat.normalized().toRotationMatrix();
      out.viewpoint.translation() = Eigen::Vector3d(t[0], t[1], t[2]);
    } else if (key == "DATA") {
      if (!(ss >> h.data)) failAt(path, line_no, "DATA without a layout");
      h.data_begin = std::min(pos, buf.size());
      h.data_line = line_no + 1;
    } else if (key != "VERSION") {
      failAt(path, line_no, "not a PCD header line: '" + line.substr(0, 40) + "'");
    }
  }
  if (h.data.empty()) throwFormatError(path, "not a PCD file (no DATA line)");
  if (h.data != "ascii" && h.data != "binary" && h.data != "binary_compressed")
    throwFormatError(path, "unsupported DATA " + h.data + " (ascii, binary or binary_compressed)");
  if (h.fields.empty()) throwFormatError(path, "no FIELDS line");
  if (sizes.size() != h.fields.size() || types.size() != h.fields.size() ||
      (!counts.empty() && counts.size() != h.fields.size()))
    throwFormatError(path, "FIELDS, SIZE, TYPE and COUNT have different lengths");
  for (std::size_t i = 0; i < h.fields.size(); i++) {
    PcdField& f = h.fields[i];
    f.size = sizes[i];
    f.type = types[i].size() == 1 ? types[i][0] : '?';
    f.count = counts.empty() ? 1 : counts[i];
    if (!supported(f.type, f.size))
      throwFormatError(path, "field '" + f.name + "': unsupported TYPE " + types[i] +
                                 " with SIZE " + std::to_string(f.size));
    if (f.count == 0 || f.count > 1000000)
      throwFormatError(path, "field '" + f.name + "' has COUNT " + std::to_string(f.count));
    f.offset = h.record;
    f.value = h.values;
    h.record += f.size * f.count;
    h.values += f.count;
  }
  // Files before v0.7 may give only POINTS (then WIDTH = POINTS, HEIGHT = 1) or only WIDTH.
  h.height = height.value_or(1);
  if (!width && !points) throwFormatError(path, "neither WIDTH nor POINTS given");
  h.width = width.value_or(h.height ? *points / h.height : 0);
  constexpr std::size_t kMax = std::numeric_limits<std::uint32_t>::max();
  if (h.width > kMax || h.height > kMax || h.width * h.height > kMax)
    throwFormatError(path, "WIDTH x HEIGHT is over 2^32 points");
  h.points = points.value_or(h.width * h.height);
  if (h.points != h.width * h.height)
    throwFormatError(path, "POINTS " + std::to_string(h.points) + " != WIDTH " +
                               std::to_string(h.width) + " x HEIGHT " + std::to_string(h.height));
  return h;
}

double readScalar(const std::uint8_t* p, const PcdField& f) {
  const auto get = [p](auto v) {
    std::memcpy(&v, p, sizeof(v));  // PCD stores the host layout; every target is little-endian
    return static_cast<double>(v);
  };
  switch (f.type == 'F' ? f.size : f.type == 'U' ? 10 + f.size : 20 + f.size) {
    case 4:
      return get(float{});
    case 8:
      return get(double{});
    case 11:
      return get(std::uint8_t{});
    case 12:
      return get(std::uint16_t{});
    case 14:
      return get(std::uint32_t{});
    case 18:
      return get(std::uint64_t{});
    case 21:
      return get(std::int8_t{});
    case 22:
      return get(std::int16_t{});
    case 24:
      return get(std::int32_t{});
    default:
      return get(std::int64_t{});
  }
}

}  // namespace dynobj::io::detail
