// SPDX-License-Identifier: BSD-3-Clause
// Velodyne beam tables and firing timing, per model. Sources (Velodyne user manuals; the tables
// are the manuals' published nominal values, not a particular unit's calibration):
//  - VLP-16: "VLP-16 User Manual" 63-9243 Rev E, Table 9-1 (elevations; no azimuth offsets) and
//    section 9.5 (firing timing: 2.304 us per laser, 55.296 us per firing, two firings a block).
//  - Puck Hi-Res: "Puck Hi-Res User Manual" 63-9318, the same layout and timing as the VLP-16
//    with elevations -10 .. +10 deg.
//  - HDL-32E: "HDL-32E User Manual" 63-9113 and application note 63-9277 Rev D, laser table
//    (elevations -30.67 .. +10.67 deg) and timing (1.152 us per laser, 46.080 us per firing).
//  - VLP-32C: "VLP-32C User Manual" 63-9325, Table 9-1 (elevation and azimuth offset per laser
//    id), timing section (lasers fire in pairs, 2.304 us per pair, 55.296 us per firing).
//  - HDL-64E S2 / S3: "HDL-64E S2" and "HDL-64E S3 User's Manual", laser firing time table
//    (upper and lower block fire together; S2 48 us, S3 57.6 us per firing). No beam table: each
//    unit ships its own calibration (db.xml), which the importer takes with --calib.
//  - VLS-128 (Alpha Prime): "VLS-128 User Manual" 63-9480, laser table (elevation, azimuth
//    offset: eight lasers per firing group, -6.354 .. +6.354 deg) and timing (firing groups of
//    eight lasers 2.665 us apart, 53.3 us per firing of all 128 incl. two maintenance groups).
// Azimuth corrections are stored in the sign of Velodyne's calibration files (rotCorrection,
// subtracted from the firing azimuth); the manuals' "azimuth offset" columns carry the other
// sign. Transcription: the VLP-16, Puck Hi-Res and HDL-32E tables are short and well known (the
// VLP-16 and HDL-32E ones are checked in the tests against MRPT 2.5's built-in defaults); the
// VLP-32C and VLS-128 tables and the HDL-64E / VLS-128 timing were taken from the public
// transcription of those manuals in github.com/valgur/velodyne_decoder (src/calib_db.cpp,
// buildTimings), the manuals themselves not being at hand here.
#include "dynobj/io/VelodyneSensor.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace dynobj::io {
namespace {

const std::vector<double> kVlp16Elevation = {-15, 1, -13, 3,  -11, 5,  -9, 7,
                                             -7,  9, -5,  11, -3,  13, -1, 15};
const std::vector<double> kPuckHiResElevation = {-10, 0.667, -8.667, 2, -7.333, 3.333,
                                                 -6,  4.667, -4.667, 6, -3.333, 7.333,
                                                 -2,  8.667, -0.667, 10};
const std::vector<double> kHdl32Elevation = {
    -30.67, -9.33,  -29.33, -8.00,  -28.00, -6.67,  -26.67, -5.33,  -25.33, -4.00,  -24.00,
    -2.67,  -22.67, -1.33,  -21.33, 0.00,   -20.00, 1.33,   -18.67, 2.67,   -17.33, 4.00,
    -16.00, 5.33,   -14.67, 6.67,   -13.33, 8.00,   -12.00, 9.33,   -10.67, 10.67};
const std::vector<double> kVlp32cElevation = {
    -25,    -1,     -1.667, -15.639, -11.31, 0,      -0.667, -8.843, -7.254, 0.333,  -0.333,
    -6.148, -5.333, 1.333,  0.667,   -4,     -4.667, 1.667,  1,      -3.667, -3.333, 3.333,
    2.333,  -2.667, -3,     7,       4.667,  -2.333, -2,     15,     10.333, -1.333};
// The manual's azimuth offsets are the negatives of these (laser 0: +1.4 deg).
const std::vector<double> kVlp32cAzimuthCorrection = {
    -1.4, 4.2, -1.4, 1.4, -1.4, 1.4, -4.2, 1.4, -1.4, 4.2, -1.4, 1.4, -4.2, 1.4, -4.2, 1.4,
    -1.4, 4.2, -1.4, 4.2, -4.2, 1.4, -1.4, 1.4, -1.4, 1.4, -1.4, 4.2, -4.2, 1.4, -1.4, 1.4};
const std::vector<double> kVls128Elevation = {
    -11.742, -1.99,   3.4,   -5.29,   -0.78, 4.61,  -4.08,   1.31,   -6.5,  -1.11,   4.28,  -4.41,
    0.1,     6.48,    -3.2,  2.19,    -3.86, 1.53,  -9.244,  -1.77,  2.74,  -5.95,   -0.56, 4.83,
    -2.98,   2.41,    -6.28, -0.89,   3.62,  -5.07, 0.32,    7.58,   -0.34, 5.18,    -3.64, 1.75,
    -25,     -2.43,   2.96,  -5.73,   0.54,  9.7,   -2.76,   2.63,   -7.65, -1.55,   3.84,  -4.85,
    3.18,    -5.51,   -0.12, 5.73,    -4.3,  1.09,  -16.042, -2.21,  4.06,  -4.63,   0.76,  15,
    -3.42,   1.97,    -6.85, -1.33,   -5.62, -0.23, 5.43,    -3.53,  0.98,  -19.582, -2.32, 3.07,
    -4.74,   0.65,    11.75, -2.65,   1.86,  -7.15, -1.44,   3.95,   -2.1,  3.29,    -5.4,  -0.01,
    4.5,     -4.19,   1.2,   -13.565, -1.22, 4.17,  -4.52,   0.87,   6.08,  -3.31,   2.08,  -6.65,
    1.42,    -10.346, -1.88, 3.51,    -6.06, -0.67, 4.72,    -3.97,  2.3,   -6.39,   -1,    4.39,
    -5.18,   0.21,    6.98,  -3.09,   4.98,  -3.75, 1.64,    -8.352, -2.54, 2.85,    -5.84, -0.45,
    8.43,    -2.87,   2.52,  -6.17,   -1.66, 3.73,  -4.96,   0.43,
};
// VLS-128: the correction repeats with the laser's place in its firing group of eight.
const double kVls128GroupCorrection[8] = {-6.354, -4.548, -2.732, -0.911,
                                          0.911,  2.732,  4.548,  6.354};

std::string normalized(const std::string& s) {
  std::string out;
  for (char c : s)
    if (c != '-' && c != '_' && c != ' ')
      out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  return out;
}

}  // namespace

VelodyneSensor VelodyneSensor::of(VelodyneModel model) {
  VelodyneSensor s;
  s.model = model;
  const auto fill_time = [&s](const auto& time_of) {
    s.laser_time_us.resize(static_cast<std::size_t>(s.lasers));
    for (int l = 0; l < s.lasers; l++) s.laser_time_us[static_cast<std::size_t>(l)] = time_of(l);
  };
  switch (model) {
    case VelodyneModel::VLP16:
    case VelodyneModel::PuckHiRes:
      s.name = model == VelodyneModel::VLP16 ? "VLP-16" : "Puck Hi-Res";
      s.product_id = model == VelodyneModel::VLP16 ? 0x22 : 0x24;
      s.lasers = 16;
      s.firings_per_block = 2;
      s.firing_period_us = 55.296;
      s.distance_unit_m = 0.002;
      s.max_range_m = 100;
      s.elevation_deg = model == VelodyneModel::VLP16 ? kVlp16Elevation : kPuckHiResElevation;
      fill_time([](int l) { return 2.304 * l; });
      break;
    case VelodyneModel::HDL32E:
      s.name = "HDL-32E";
      s.product_id = 0x21;
      s.lasers = 32;
      s.firing_period_us = 46.080;
      s.distance_unit_m = 0.002;
      s.max_range_m = 100;
      s.elevation_deg = kHdl32Elevation;
      fill_time([](int l) { return 1.152 * l; });
      break;
    case VelodyneModel::VLP32C:
      s.name = "VLP-32C";
      s.product_id = 0x28;
      s.lasers = 32;
      s.firing_period_us = 55.296;
      s.distance_unit_m = 0.004;
      s.max_range_m = 200;
      s.elevation_deg = kVlp32cElevation;
      s.azimuth_correction_deg = kVlp32cAzimuthCorrection;
      fill_time([](int l) { return 2.304 * (l / 2); });
      break;
    case VelodyneModel::HDL64E_S2:
    case VelodyneModel::HDL64E_S3: {
      const bool s3 = model == VelodyneModel::HDL64E_S3;
      s.name = s3 ? "HDL-64E S3" : "HDL-64E S2";
      s.lasers = 64;
      s.blocks_per_firing = 2;
      s.firing_period_us = s3 ? 57.6 : 48.0;
      s.distance_unit_m = 0.002;
      s.max_range_m = 120;
      // Laser j of each block (upper 0-31, lower 32-63 fire together): groups of four.
      const double s2[4] = {0, 1.26, 2.46, 3.66}, s3t[4] = {0, 1.3, 2.5, 3.7};
      fill_time([&](int l) {
        const int j = l % 32;
        return (s3 ? 7.2 : 6.0) * (j / 4) + (s3 ? s3t : s2)[j % 4];
      });
      break;
    }
    case VelodyneModel::VLS128:
      s.name = "VLS-128";
      s.product_id = 0xA1;
      s.lasers = 128;
      s.blocks_per_firing = 4;
      s.firing_period_us = 53.3;
      s.distance_unit_m = 0.004;
      s.max_range_m = 245;
      s.elevation_deg = kVls128Elevation;
      for (int l = 0; l < 128; l++)
        s.azimuth_correction_deg.push_back(kVls128GroupCorrection[l % 8]);
      // Groups of eight; after the eighth group come two maintenance slots.
      fill_time([](int l) { return 2.665 * (l / 8 + (l / 64) * 2); });
      break;
  }
  if (s.azimuth_correction_deg.empty() && !s.elevation_deg.empty())
    s.azimuth_correction_deg.assign(s.elevation_deg.size(), 0.0);
  return s;
}

std::optional<VelodyneModel> VelodyneSensor::fromName(const std::string& name) {
  const std::string n = normalized(name);
  if (n == "vlp16") return VelodyneModel::VLP16;
  if (n == "puckhires" || n == "vlp16hires") return VelodyneModel::PuckHiRes;
  if (n == "vlp32c") return VelodyneModel::VLP32C;
  if (n == "hdl32e" || n == "hdl32") return VelodyneModel::HDL32E;
  if (n == "hdl64es2") return VelodyneModel::HDL64E_S2;
  if (n == "hdl64es3" || n == "hdl64e" || n == "hdl64") return VelodyneModel::HDL64E_S3;
  if (n == "vls128" || n == "alphaprime") return VelodyneModel::VLS128;
  return std::nullopt;
}

std::optional<VelodyneModel> VelodyneSensor::fromProductId(std::uint8_t id) {
  switch (id) {
    case 0x21:
      return VelodyneModel::HDL32E;
    case 0x22:
      return VelodyneModel::VLP16;
    case 0x24:
      return VelodyneModel::PuckHiRes;
    case 0x28:
      return VelodyneModel::VLP32C;
    case 0xA1:
      return VelodyneModel::VLS128;
    default:
      return std::nullopt;
  }
}

std::string VelodyneSensor::modelNames() {
  return "vlp-16, puck-hi-res, vlp-32c, hdl-32e, hdl-64e-s2, hdl-64e-s3, vls-128";
}

double VelodyneSensor::packetPeriodUs(bool dual) const {
  const double firings = 12.0 * firings_per_block / blocks_per_firing;
  return (dual ? firings / 2 : firings) * firing_period_us;
}

core::SensorModel VelodyneSensor::sensorModel(int cols, double frequency_hz) const {
  core::SensorModel m;
  m.model = name;
  m.rows = lasers;
  m.cols = cols;
  m.beam_elevations.clear();
  for (double e : elevation_deg) m.beam_elevations.push_back(e * M_PI / 180.0);
  m.min_range = 0.5;
  m.max_range = max_range_m;
  m.frequency = frequency_hz;
  return m;
}

}  // namespace dynobj::io
