// SPDX-License-Identifier: BSD-3-Clause
// readPcd: after the header (PcdHeader.cpp) the points come in one of three layouts: ascii (one
// point per line), binary (packed records, point-major) or binary_compressed (uint32 compressed
// size, uint32 uncompressed size, then LZF data that expands to field-major arrays: every point's
// first field, then every point's second field, ...).
#include "dynobj/io/PcdFile.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>

#include "Lzf.h"
#include "PcdHeader.h"

namespace dynobj::io {
namespace {

using detail::PcdField;
using detail::PcdHeader;

/// The first of `names` present as a scalar field (name set in `which`), or nullptr.
const PcdField* findField(const PcdHeader& h, std::initializer_list<const char*> names,
                          std::string* which = nullptr) {
  for (const char* n : names)
    for (const PcdField& f : h.fields)
      if (f.name == n && f.count == 1) {
        if (which) *which = n;
        return &f;
      }
  return nullptr;
}

bool isBlank(char c) {
  return c == ' ' || c == '\t' || c == '\r';
}

/// Ascii data: every value of every point, point-major (points x values). Blank lines are skipped.
std::vector<double> parseAscii(const std::string& path, const std::string& buf,
                               const PcdHeader& h) {
  std::vector<double> v;
  v.reserve(std::min(h.points * h.values, (buf.size() - h.data_begin) / 2 + 1));
  std::size_t pos = h.data_begin, line_no = h.data_line, n = 0;
  for (; n < h.points && pos < buf.size(); line_no++) {
    const char* const end = buf.data() + std::min(buf.find('\n', pos), buf.size());
    std::size_t found = 0;
    for (const char* p = buf.data() + pos;; found++) {
      while (p < end && isBlank(*p)) p++;
      if (p == end) break;
      double x = 0;
      const auto r = std::from_chars(p + (*p == '+'), end, x);
      if (r.ec != std::errc() || (r.ptr != end && !isBlank(*r.ptr)))
        detail::failAt(path, line_no,
                       "'" + std::string(p, std::find_if(p, end, isBlank)) + "' is not a number");
      v.push_back(x);
      p = r.ptr;
    }
    pos = static_cast<std::size_t>(end - buf.data()) + 1;
    if (found == 0) continue;
    if (found != h.values)
      detail::failAt(
          path, line_no,
          "expected " + std::to_string(h.values) + " values, found " + std::to_string(found));
    n++;
  }
  if (n < h.points)
    throwFormatError(path, "ascii data is truncated: " + std::to_string(n) + " of POINTS " +
                               std::to_string(h.points) + " points");
  return v;
}

/// binary_compressed data expanded into field-major arrays of h.points * h.record bytes.
std::vector<std::uint8_t> decompress(const std::string& path, const std::string& buf,
                                     const PcdHeader& h) {
  const std::size_t left = buf.size() - h.data_begin;
  if (left < 8) throwFormatError(path, "binary_compressed data is truncated (no size header)");
  std::uint32_t sizes[2];
  std::memcpy(sizes, buf.data() + h.data_begin, sizeof(sizes));
  if (sizes[0] > left - 8)
    throwFormatError(path, "binary_compressed: compressed size " + std::to_string(sizes[0]) +
                               " exceeds the " + std::to_string(left - 8) +
                               " bytes left in the file");
  if (sizes[1] != h.points * h.record)
    throwFormatError(path,
                     "binary_compressed: uncompressed size " + std::to_string(sizes[1]) +
                         " != POINTS x bytes per point = " + std::to_string(h.points * h.record));
  if (sizes[1] / 88 > sizes[0])  // an LZF command expands 3 bytes into at most 264
    throwFormatError(path, "binary_compressed: " + std::to_string(sizes[0]) +
                               " compressed bytes cannot expand to " + std::to_string(sizes[1]));
  std::vector<std::uint8_t> out(sizes[1]);
  const auto* in = reinterpret_cast<const std::uint8_t*>(buf.data() + h.data_begin + 8);
  const std::string problem = detail::lzfDecompress(in, sizes[0], out.data(), out.size());
  if (!problem.empty()) throwFormatError(path, "binary_compressed: " + problem);
  return out;
}

/// time_s from raw stamps [s]; absolute stamps (epoch) become relative to the earliest point.
void setTimes(const std::vector<double>& t, CloudFile& c) {
  const auto [lo, hi] = std::minmax_element(t.begin(), t.end());
  const double origin = t.empty() || std::max(std::abs(*lo), std::abs(*hi)) <= 1e6 ? 0.0 : *lo;
  c.time_origin_ns = std::llround(origin * 1e9);
  c.time_s.reserve(t.size());
  for (double v : t) c.time_s.push_back(static_cast<float>(v - origin));
}

}  // namespace

CloudFile readPcd(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throwFormatError(path, "cannot open PCD file");
  const std::streamoff size = in.tellg();
  if (size < 0) throwFormatError(path, "cannot read PCD file");
  std::string buf(static_cast<std::size_t>(size), '\0');
  in.seekg(0);
  if (!in.read(buf.data(), static_cast<std::streamsize>(buf.size())))
    throwFormatError(path, "read error");
  CloudFile out;
  const PcdHeader h = detail::parsePcdHeader(path, buf, out);
  out.width = h.width;
  out.height = h.height;
  const PcdField* fx = findField(h, {"x"});
  const PcdField* fy = findField(h, {"y"});
  const PcdField* fz = findField(h, {"z"});
  for (const auto& [f, n] : {std::pair{fx, "x"}, {fy, "y"}, {fz, "z"}})
    if (!f) throwFormatError(path, std::string("no field '") + n + "' (with COUNT 1)");
  const PcdField* fi = findField(h, {"intensity", "i", "reflectivity"}, &out.intensity_field);
  const PcdField* fr = findField(h, {"ring"});
  const PcdField* ft = findField(h, {"t", "time", "timestamp"}, &out.time_field);
  const double time_unit = ft && ft->type != 'F' ? 1e-9 : 1.0;  // integer stamps are ns
  if (h.record > 0 && h.points > std::numeric_limits<std::size_t>::max() / h.record)
    throwFormatError(path, "POINTS x bytes per point overflows");

  std::vector<double> ascii;
  std::vector<std::uint8_t> unpacked;
  const std::uint8_t* bytes = reinterpret_cast<const std::uint8_t*>(buf.data() + h.data_begin);
  if (h.data == "ascii") {
    ascii = parseAscii(path, buf, h);
  } else if (h.data == "binary") {
    const std::size_t left = buf.size() - h.data_begin;  // more is padding (PCL pads files)
    if (h.points * h.record > left)
      throwFormatError(path, "binary data is truncated: POINTS " + std::to_string(h.points) +
                                 " need " + std::to_string(h.points * h.record) + " bytes, " +
                                 std::to_string(left) + " follow the header");
  } else {
    unpacked = decompress(path, buf, h);
    bytes = unpacked.data();
  }
  const bool is_ascii = h.data == "ascii", field_major = h.data == "binary_compressed";
  const auto get = [&](const PcdField& f, std::size_t i) {
    if (is_ascii) return ascii[i * h.values + f.value];
    return detail::readScalar(
        field_major ? bytes + h.points * f.offset + i * f.size : bytes + i * h.record + f.offset,
        f);
  };

  core::PointCloud& c = out.cloud;
  c.reserve(h.points, fi != nullptr, false);
  if (fr) c.ring.reserve(h.points);
  std::vector<double> times;
  for (std::size_t i = 0; i < h.points; i++) {
    const auto x = static_cast<float>(get(*fx, i)), y = static_cast<float>(get(*fy, i)),
               z = static_cast<float>(get(*fz, i));
    if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) {
      out.dropped_nonfinite++;  // also F8 values beyond float range
      continue;
    }
    c.push_back(x, y, z);
    if (fi) c.intensity.push_back(static_cast<float>(get(*fi, i)));
    if (fr) {
      const double r = get(*fr, i);
      if (!(r >= 0 && r <= 65535 && r == std::floor(r)))
        throwFormatError(path, "point " + std::to_string(i) + ": ring " + std::to_string(r) +
                                   " is not a laser id in 0..65535");
      c.ring.push_back(static_cast<std::uint16_t>(r));
    }
    if (ft) times.push_back(get(*ft, i) * time_unit);
  }
  if (ft) setTimes(times, out);
  return out;
}

}  // namespace dynobj::io
