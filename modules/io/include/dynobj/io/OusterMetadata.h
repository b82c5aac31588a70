// SPDX-License-Identifier: BSD-3-Clause
// The sensor metadata JSON an Ouster sensor (or its SDK) writes next to a pcap capture: image
// size, packet profile, destagger shifts, beam angles, lidar-to-sensor transform.
//
// Accepted layouts: the flat SDK JSON (FW >= 2.0, `data_format` block), the reduced legacy JSON
// without `data_format` (SDK defaults: rows = number of beam angles, shifts [9,6,3,0] / [18,12,6,0]
// / [36,24,12,0] repeated for 512 / 1024 / 2048 columns, profile LEGACY), and the nested layout
// of newer SDKs (`sensor_info`, `beam_intrinsics`, `lidar_intrinsics`, `config_params`,
// `lidar_data_format` objects), which is flattened first.
// Required keys: lidar_mode, beam_altitude_angles, beam_azimuth_angles; inside a present
// data_format: pixels_per_column, columns_per_frame, columns_per_packet, pixel_shift_by_row.
// Bounds: 1-256 rows, 8-4096 columns (Ouster: up to 128 beams, 4096x5), shifts in (-W, W),
// beam altitudes strictly decreasing (row 0 = top: cloud rows are beam indices).
// Optional keys take the SDK's defaults (lidar_origin_to_beam_origin_mm by product line:
// OS-0 27.67, OS-1 15.806, OS-2 13.762, else 12.163; lidar_to_sensor_transform = 180 deg yaw +
// 36.18 mm up; column_window = all columns; udp_profile_lidar = LEGACY; udp_port_lidar = 7502).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "dynobj/core/SensorModel.h"

namespace dynobj::io {

struct OusterMetadata {
  std::string prod_line;   ///< e.g. "OS-1-128" (empty in the reduced JSON)
  std::string firmware;    ///< build_rev, e.g. "v2.3.0" (may be empty)
  std::string lidar_mode;  ///< e.g. "1024x10"
  int rows = 0;            ///< pixels_per_column (beams)
  int cols = 0;            ///< columns_per_frame
  int columns_per_packet = 16;
  /// Lidar packet profile: "LEGACY", "RNG19_RFL8_SIG16_NIR16" or "RNG15_RFL8_NIR8".
  std::string profile = "LEGACY";
  /// Destagger shift of each row, normalised to [0, cols).
  std::vector<int> pixel_shift_by_row;
  /// [deg] Per row (row 0 = top beam): elevation, and azimuth offset of the beam.
  std::vector<double> beam_altitude_deg, beam_azimuth_deg;
  /// [mm] Radius of the beam origins around the lidar axis.
  double lidar_origin_to_beam_origin_mm = 0;
  /// [mm] Height of the beam origins above the lidar origin (beam_to_lidar_transform (2,3) of
  /// newer JSONs; 0 otherwise).
  double beam_origin_z_mm = 0;
  /// Lidar frame -> sensor frame; translation in mm, as in the JSON.
  Eigen::Matrix4d lidar_to_sensor = Eigen::Matrix4d::Identity();
  /// First / last measurement id the sensor sends (inclusive; may wrap past cols - 1).
  int column_window_first = 0, column_window_last = -1;
  int udp_port_lidar = 7502;
  std::uint32_t initialization_id = 0;  ///< 0 = not in the JSON
  std::uint64_t serial_number = 0;      ///< prod_sn; 0 = not in the JSON
  double frequency_hz = 10;             ///< revolutions per second, from lidar_mode

  /// Reads and validates a metadata JSON. Throws FormatError("<path>: <key>: <problem>") for a
  /// missing or malformed key, wrong array lengths, shifts out of range, unknown profiles.
  static OusterMetadata load(const std::string& json_path);
  /// Same from JSON text; `source` names it in errors.
  static OusterMetadata parse(const std::string& json_text, const std::string& source);

  /// The sensor model of the project: model = prod_line ("Ouster" if unknown), rows, cols,
  /// beam_elevations = beam altitudes [rad] in row order, frequency; min_range 0.3 m; max_range
  /// by product line: OS-0 75 m, OS-1 120 m, OS-2 240 m, unknown 120 m (nominal figures, the
  /// presets in share/dynobj/sensors use 75 and 120; the projection does not clip to them).
  core::SensorModel sensorModel() const;

  bool hasSignal() const { return profile != "RNG15_RFL8_NIR8"; }
  /// Expected size of one lidar UDP payload [bytes] for this profile, rows and columns/packet.
  std::size_t lidarPacketSize() const;
  /// Number of measurement ids inside the column window.
  int columnWindowWidth() const;
  /// The column layout of docs/formats.md Eq. (1) from the destaggered Ouster column c:
  /// eq1Column(c) = (eq1ColumnBase() - c) mod cols. The destaggered image runs clockwise from
  /// (about) the sensor's -X axis; Eq. (1) runs counter-clockwise from azimuth -pi. The base
  /// follows from the lidar_to_sensor yaw and the mean of (2 pi shift/cols - beam azimuth).
  int eq1ColumnBase() const;
  int eq1Column(int destaggered_col) const;
};

}  // namespace dynobj::io
