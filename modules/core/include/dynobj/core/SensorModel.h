// SPDX-License-Identifier: BSD-3-Clause
// The geometry of a spinning multi-beam LiDAR: how many beams (image rows), how many azimuth bins
// per revolution (image columns), and the elevation of each beam. Loaded from the presets in
// share/dynobj/sensors/*.ini (MRPT INI convention: degrees in files, radians in memory).
#pragma once

#include <mrpt/config/CLoadableOptions.h>

#include <string>
#include <vector>

namespace dynobj::core {

struct SensorModel : public ::mrpt::config::CLoadableOptions {
  /// Free-form model name, e.g. "OS0-64" (INI key `model`).
  std::string model = "OS0-64";
  /// Number of beams = image rows H. Row 0 is the highest beam (INI key `rows`).
  int rows = 64;
  /// Azimuth bins per revolution = image columns W (INI key `cols`).
  int cols = 1024;
  /// [rad; degrees in INI] Elevation of the highest / lowest beam centre for sensors with evenly
  /// spaced beams (INI keys `elevation_top`, `elevation_bottom`). Ignored if beam_elevations is
  /// set.
  double elevation_top = 45.0 * 3.14159265358979323846 / 180.0;
  double elevation_bottom = -45.0 * 3.14159265358979323846 / 180.0;
  /// [rad; degrees in INI] Optional per-laser elevation table in *laser-id order* (the order of
  /// the sensor's own ring / laser numbers, e.g. a VLP-16 interleaves -15, 1, -13, 3, ...).
  /// Empty = evenly spaced beams (INI key `beam_elevations`, a list).
  std::vector<double> beam_elevations;
  /// [m] Physical range limits of the sensor (INI keys `min_range`, `max_range`).
  double min_range = 0.3;
  double max_range = 100.0;
  /// [Hz] Revolutions per second (INI key `frequency`).
  double frequency = 10.0;

  void loadFromConfigFile(const ::mrpt::config::CConfigFileBase& source,
                          const std::string& section) override;
  void saveToConfigFile(::mrpt::config::CConfigFileBase& target,
                        const std::string& section) const override;
  /// Throws ParameterError naming the first bad key.
  void validate() const;
  /// The INI keys loadFromConfigFile() reads (what a strict reader accepts in a preset).
  static const std::vector<std::string>& iniKeys();

  /// True when beams are evenly spaced (no table): rows follow Eq. (1) exactly.
  bool isUniform() const { return beam_elevations.empty(); }
  /// Beam centre elevations ordered by image row (row 0 = highest) [rad].
  std::vector<double> rowElevations() const;
  /// For each laser id (index into beam_elevations), its image row. Identity for uniform sensors.
  std::vector<int> laserToRow() const;
  /// beta_up of Eq. (1) [rad]: upper edge of row 0, half a beam spacing above the top beam.
  double fovUp() const;
  /// beta_fov of Eq. (1) [rad]: total vertical extent of the image, rows x beam spacing.
  double fovSpan() const;
};

}  // namespace dynobj::core
