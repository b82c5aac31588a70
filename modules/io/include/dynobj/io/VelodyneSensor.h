// SPDX-License-Identifier: BSD-3-Clause
// What a Velodyne data packet means for each supported model: beam table (elevation and azimuth
// correction per laser id), firing timing, distance unit, how the 12 blocks of a packet group
// into firings, and the factory bytes (product id) that name the model. Sources of every table:
// VelodyneSensor.cpp. Knows no MRPT and no pcap.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/core/SensorModel.h"

namespace dynobj::io {

enum class VelodyneModel { VLP16, PuckHiRes, VLP32C, HDL32E, HDL64E_S2, HDL64E_S3, VLS128 };

struct VelodyneSensor {
  VelodyneModel model = VelodyneModel::VLP16;
  std::string name;  ///< e.g. "VLP-16"
  int lasers = 0;
  /// Blocks holding one firing of all lasers: 1, 2 (HDL-64E upper 0xEEFF + lower 0xDDFF) or 4
  /// (VLS-128 banks 0xEEFF, 0xDDFF, 0xCCFF, 0xBBFF).
  int blocks_per_firing = 1;
  /// Firings in one block: 2 for the 16-laser Pucks (channels 0-15, then 16-31), else 1.
  int firings_per_block = 1;
  double firing_period_us = 0;  ///< [us] one firing of all lasers, recharge included
  double distance_unit_m = 0;   ///< [m] per distance count
  double max_range_m = 100;     ///< [m] datasheet range
  std::uint8_t product_id = 0;  ///< factory byte 1205; 0 = the model does not send one
  /// [deg] Per laser id: elevation, and the azimuth correction of Velodyne's calibration files
  /// (rotCorrection: a laser fires at azimuth(firing) - correction). Empty for HDL-64E: its beam
  /// table is unit-specific (the db.xml shipped with each unit).
  std::vector<double> elevation_deg, azimuth_correction_deg;
  /// [us] Per laser id: when it fires after the start of its firing.
  std::vector<double> laser_time_us;

  static VelodyneSensor of(VelodyneModel model);
  /// "vlp-16", "puck-hi-res", "vlp-32c", "hdl-32e", "hdl-64e-s2", "hdl-64e-s3", "vls-128"
  /// (case-insensitive, '-' and '_' optional); nullopt for anything else.
  static std::optional<VelodyneModel> fromName(const std::string& name);
  /// The model named by factory byte 1205 (0x21 HDL-32E, 0x22 VLP-16, 0x24 Puck Hi-Res,
  /// 0x28 VLP-32C, 0xA1 VLS-128); nullopt for 0 and unknown ids.
  static std::optional<VelodyneModel> fromProductId(std::uint8_t id);
  /// The accepted names, for messages.
  static std::string modelNames();

  /// [us] Sensor time between two data packets: 12 blocks of firings (half as many firings in
  /// dual-return mode, where each firing fills two blocks).
  double packetPeriodUs(bool dual) const;
  /// The project's sensor model: rows = lasers, beam_elevations = the elevation table (laser-id
  /// order), cols and frequency as measured.
  core::SensorModel sensorModel(int cols, double frequency_hz) const;
};

}  // namespace dynobj::io
