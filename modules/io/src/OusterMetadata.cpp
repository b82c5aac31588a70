// SPDX-License-Identifier: BSD-3-Clause
// Ouster metadata JSON -> OusterMetadata, with every key checked (see the header for the rules).
#include "dynobj/io/OusterMetadata.h"

#include <Eigen/LU>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "dynobj/io/FormatError.h"

namespace dynobj::io {
namespace {

using Json = nlohmann::json;

struct Reader {
  const std::string& source;
  [[noreturn]] void fail(const std::string& key, const std::string& problem) const {
    throwFormatError(source, key + ": " + problem);
  }
  const Json& require(const Json& obj, const std::string& key, const std::string& prefix) const {
    auto it = obj.find(key);
    if (it == obj.end()) fail(prefix + key, "missing key");
    return *it;
  }
  double number(const Json& v, const std::string& key) const {
    if (!v.is_number()) fail(key, "expected a number, got " + std::string(v.type_name()));
    const double d = v.get<double>();
    if (!std::isfinite(d)) fail(key, "not a finite number");
    return d;
  }
  int integer(const Json& v, const std::string& key, long lo, long hi) const {
    if (!v.is_number_integer()) fail(key, "expected an integer, got " + v.dump());
    const long long i = v.get<long long>();
    if (i < lo || i > hi) {
      fail(key, std::to_string(i) + " is out of range [" + std::to_string(lo) + ", " +
                    std::to_string(hi) + "]");
    }
    return static_cast<int>(i);
  }
  std::string text(const Json& v, const std::string& key) const {
    if (!v.is_string()) fail(key, "expected a string, got " + std::string(v.type_name()));
    return v.get<std::string>();
  }
  std::vector<double> numbers(const Json& v, const std::string& key, std::size_t n) const {
    if (!v.is_array()) fail(key, "expected an array, got " + std::string(v.type_name()));
    if (v.size() != n)
      fail(key, "has " + std::to_string(v.size()) + " entries, expected " + std::to_string(n));
    std::vector<double> out;
    for (std::size_t i = 0; i < v.size(); i++)
      out.push_back(number(v[i], key + "[" + std::to_string(i) + "]"));
    return out;
  }
};

// The nested layout of newer SDKs -> the flat one (same key names inside the blocks).
Json flatten(const Json& root) {
  if (!root.contains("sensor_info") || !root["sensor_info"].is_object()) return root;
  Json flat = Json::object();
  for (const char* block : {"sensor_info", "beam_intrinsics", "lidar_intrinsics"}) {
    if (root.contains(block) && root[block].is_object()) flat.update(root[block]);
  }
  if (root.contains("config_params") && root["config_params"].is_object()) {
    for (const char* key : {"lidar_mode", "udp_port_lidar"})
      if (root["config_params"].contains(key)) flat[key] = root["config_params"][key];
  }
  if (root.contains("lidar_data_format")) flat["data_format"] = root["lidar_data_format"];
  return flat;
}

double defaultBeamOrigin(const std::string& prod_line) {
  if (prod_line.rfind("OS-0-", 0) == 0) return 27.67;
  if (prod_line.rfind("OS-1-", 0) == 0) return 15.806;
  if (prod_line.rfind("OS-2-", 0) == 0) return 13.762;
  return 12.163;  // gen-1 sensors
}

std::vector<int> defaultShifts(int rows, int cols, const Reader& r) {
  int step = 0;
  if (cols == 512) step = 3;
  if (cols == 1024) step = 6;
  if (cols == 2048) step = 12;
  if (step == 0)
    r.fail("data_format", "missing, and there are no default pixel shifts for " +
                              std::to_string(cols) + " columns");
  std::vector<int> s(static_cast<std::size_t>(rows));
  for (int u = 0; u < rows; u++) s[static_cast<std::size_t>(u)] = (3 - u % 4) * step;
  return s;
}

void parseDataFormat(const Json& root, const Reader& r, OusterMetadata& m) {
  const int cols_of_mode = m.cols;
  if (!root.contains("data_format")) {
    m.rows = static_cast<int>(r.require(root, "beam_altitude_angles", "").size());
    if (m.rows < 1 || m.rows > 256) r.fail("beam_altitude_angles", "expected 1 to 256 entries");
    m.pixel_shift_by_row = defaultShifts(m.rows, m.cols, r);
    m.column_window_last = m.cols - 1;
    return;
  }
  const Json& df = root["data_format"];
  if (!df.is_object()) r.fail("data_format", "expected an object");
  const std::string p = "data_format.";
  m.rows = r.integer(r.require(df, "pixels_per_column", p), p + "pixels_per_column", 1, 256);
  m.cols = r.integer(r.require(df, "columns_per_frame", p), p + "columns_per_frame", 8, 4096);
  if (m.cols != cols_of_mode)
    r.fail(p + "columns_per_frame", std::to_string(m.cols) + " but lidar_mode is " + m.lidar_mode);
  m.columns_per_packet =
      r.integer(r.require(df, "columns_per_packet", p), p + "columns_per_packet", 1, m.cols);
  const Json& shifts = r.require(df, "pixel_shift_by_row", p);
  const auto values = r.numbers(shifts, p + "pixel_shift_by_row", static_cast<std::size_t>(m.rows));
  for (std::size_t u = 0; u < values.size(); u++) {
    const std::string key = p + "pixel_shift_by_row[" + std::to_string(u) + "]";
    const int s = r.integer(shifts[u], key, -(m.cols - 1), m.cols - 1);
    m.pixel_shift_by_row.push_back((s + m.cols) % m.cols);
  }
  m.column_window_last = m.cols - 1;
  if (df.contains("column_window")) {
    const Json& w = df["column_window"];
    if (!w.is_array() || w.size() != 2) r.fail(p + "column_window", "expected [first, last]");
    m.column_window_first = r.integer(w[0], p + "column_window[0]", 0, m.cols - 1);
    m.column_window_last = r.integer(w[1], p + "column_window[1]", 0, m.cols - 1);
  }
  if (df.contains("udp_profile_lidar")) {
    m.profile = r.text(df["udp_profile_lidar"], p + "udp_profile_lidar");
    if (m.profile != "LEGACY" && m.profile != "RNG19_RFL8_SIG16_NIR16" &&
        m.profile != "RNG15_RFL8_NIR8") {
      r.fail(p + "udp_profile_lidar", "unsupported profile '" + m.profile +
                                          "' (supported: LEGACY, RNG19_RFL8_SIG16_NIR16, "
                                          "RNG15_RFL8_NIR8)");
    }
  }
}

void parseTransform(const Json& root, const Reader& r, OusterMetadata& m) {
  m.lidar_to_sensor << -1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 36.18, 0, 0, 0, 1;  // SDK default
  if (root.contains("lidar_to_sensor_transform")) {
    const auto v = r.numbers(root["lidar_to_sensor_transform"], "lidar_to_sensor_transform", 16);
    for (int i = 0; i < 16; i++) m.lidar_to_sensor(i / 4, i % 4) = v[static_cast<std::size_t>(i)];
    const Eigen::Matrix3d rot = m.lidar_to_sensor.topLeftCorner<3, 3>();
    const bool rigid = (rot.transpose() * rot - Eigen::Matrix3d::Identity()).norm() < 1e-3 &&
                       rot.determinant() > 0 &&
                       m.lidar_to_sensor.row(3).isApprox(Eigen::RowVector4d(0, 0, 0, 1));
    if (!rigid) r.fail("lidar_to_sensor_transform", "not a rigid transform (row-major 4x4)");
  }
}

}  // namespace

OusterMetadata OusterMetadata::load(const std::string& json_path) {
  std::ifstream in(json_path, std::ios::binary);
  if (!in) throwFormatError(json_path, "cannot open the metadata file");
  std::ostringstream ss;
  ss << in.rdbuf();
  return parse(ss.str(), json_path);
}

OusterMetadata OusterMetadata::parse(const std::string& json_text, const std::string& source) {
  Json parsed;
  try {
    parsed = Json::parse(json_text);
  } catch (const Json::exception& e) {
    throwFormatError(source, std::string("not valid JSON: ") + e.what());
  }
  if (!parsed.is_object()) throwFormatError(source, "not a JSON object");
  const Json root = flatten(parsed);
  const Reader r{source};
  OusterMetadata m;
  if (root.contains("prod_line")) m.prod_line = r.text(root["prod_line"], "prod_line");
  if (root.contains("build_rev")) m.firmware = r.text(root["build_rev"], "build_rev");

  m.lidar_mode = r.text(r.require(root, "lidar_mode", ""), "lidar_mode");
  int hz = 0;
  char x = 0, extra = 0;
  std::istringstream mode(m.lidar_mode);
  if (!(mode >> m.cols >> x >> hz) || x != 'x' || (mode >> extra) || m.cols < 8 || m.cols > 4096 ||
      hz <= 0 || hz > 100)
    r.fail("lidar_mode", "'" + m.lidar_mode + "' is not <columns (8-4096)>x<Hz>");
  m.frequency_hz = hz;
  parseDataFormat(root, r, m);

  const auto n = static_cast<std::size_t>(m.rows);
  const std::string rows_txt = " (pixels_per_column = " + std::to_string(m.rows) + ")";
  const Json& alt = r.require(root, "beam_altitude_angles", "");
  const Json& azi = r.require(root, "beam_azimuth_angles", "");
  if (alt.is_array() && alt.size() != n)
    r.fail("beam_altitude_angles", "has " + std::to_string(alt.size()) + " entries" + rows_txt);
  if (azi.is_array() && azi.size() != n)
    r.fail("beam_azimuth_angles", "has " + std::to_string(azi.size()) + " entries" + rows_txt);
  m.beam_altitude_deg = r.numbers(alt, "beam_altitude_angles", n);
  m.beam_azimuth_deg = r.numbers(azi, "beam_azimuth_angles", n);
  for (std::size_t u = 0; u < n; u++) {
    if (std::abs(m.beam_altitude_deg[u]) >= 90 || std::abs(m.beam_azimuth_deg[u]) >= 180)
      r.fail("beam_altitude_angles", "angle of row " + std::to_string(u) + " out of range");
    if (u > 0 && !(m.beam_altitude_deg[u] < m.beam_altitude_deg[u - 1]))
      r.fail("beam_altitude_angles", "not strictly decreasing at row " + std::to_string(u) +
                                         " (row 0 must be the highest beam)");
  }

  m.lidar_origin_to_beam_origin_mm = defaultBeamOrigin(m.prod_line);
  if (root.contains("lidar_origin_to_beam_origin_mm"))
    m.lidar_origin_to_beam_origin_mm =
        r.number(root["lidar_origin_to_beam_origin_mm"], "lidar_origin_to_beam_origin_mm");
  if (root.contains("beam_to_lidar_transform")) {
    const auto b = r.numbers(root["beam_to_lidar_transform"], "beam_to_lidar_transform", 16);
    m.lidar_origin_to_beam_origin_mm = b[3];
    m.beam_origin_z_mm = b[11];
  }
  if (std::abs(m.lidar_origin_to_beam_origin_mm) > 1000 || std::abs(m.beam_origin_z_mm) > 1000)
    r.fail("lidar_origin_to_beam_origin_mm", "beam origin offset above 1 m");
  parseTransform(root, r, m);

  if (root.contains("udp_port_lidar")) {
    const int port = r.integer(root["udp_port_lidar"], "udp_port_lidar", 0, 65535);
    if (port != 0) m.udp_port_lidar = port;  // 0 = "not configured" in some JSONs
  }
  if (root.contains("initialization_id"))
    m.initialization_id = static_cast<std::uint32_t>(
        r.integer(root["initialization_id"], "initialization_id", 0, 0xFFFFFF));
  if (root.contains("prod_sn") && root["prod_sn"].is_string()) {
    const std::string sn = root["prod_sn"].get<std::string>();
    if (!sn.empty() && sn.size() < 19 && sn.find_first_not_of("0123456789") == std::string::npos)
      m.serial_number = std::stoull(sn);
  }
  return m;
}

core::SensorModel OusterMetadata::sensorModel() const {
  core::SensorModel s;
  s.model = prod_line.empty() ? "Ouster" : prod_line;
  s.rows = rows;
  s.cols = cols;
  s.beam_elevations.clear();
  for (double a : beam_altitude_deg) s.beam_elevations.push_back(a * M_PI / 180.0);
  if (!s.beam_elevations.empty()) {
    s.elevation_top = s.beam_elevations.front();
    s.elevation_bottom = s.beam_elevations.back();
  }
  s.min_range = 0.3;
  s.max_range = 120.0;
  if (prod_line.rfind("OS-0-", 0) == 0) s.max_range = 75.0;
  if (prod_line.rfind("OS-2-", 0) == 0) s.max_range = 240.0;
  s.frequency = frequency_hz;
  return s;
}

std::size_t OusterMetadata::lidarPacketSize() const {
  const auto h = static_cast<std::size_t>(rows);
  const auto n = static_cast<std::size_t>(columns_per_packet);
  if (profile == "LEGACY") return n * (16 + h * 12 + 4);
  const std::size_t pixel = profile == "RNG15_RFL8_NIR8" ? 4 : 12;
  return 32 + n * (12 + h * pixel) + 32;
}

int OusterMetadata::columnWindowWidth() const {
  if (cols <= 0) return 0;
  return ((column_window_last - column_window_first) % cols + cols) % cols + 1;
}

int OusterMetadata::eq1ColumnBase() const {
  if (cols <= 0) return 0;
  // Sensor azimuth of destaggered column c: yaw + 2 pi (1 - c / W) + d_u, with
  // d_u = 2 pi shift_u / W - beam azimuth_u (nearly the same for every row).
  double sx = 0, sy = 0;
  for (std::size_t u = 0; u < pixel_shift_by_row.size() && u < beam_azimuth_deg.size(); u++) {
    const double d = 2 * M_PI * pixel_shift_by_row[u] / cols - beam_azimuth_deg[u] * M_PI / 180;
    sx += std::cos(d);
    sy += std::sin(d);
  }
  const double mean_d = std::atan2(sy, sx);
  const double yaw = std::atan2(lidar_to_sensor(1, 0), lidar_to_sensor(0, 0));
  // Eq. (1): u = (azimuth + pi) / (2 pi) W = (yaw + pi + mean_d) / (2 pi) W + W - c.
  const double a = (yaw + M_PI + mean_d) / (2 * M_PI) * cols;
  const long base = static_cast<long>(std::floor(a + 1e-6));
  return static_cast<int>((base % cols + cols) % cols);
}

int OusterMetadata::eq1Column(int destaggered_col) const {
  if (cols <= 0) return 0;
  return ((eq1ColumnBase() - destaggered_col) % cols + cols) % cols;
}

}  // namespace dynobj::io
