// SPDX-License-Identifier: BSD-3-Clause
// A user's recording -> a stock MRPT rawlog (observation-only) that any dynobj tool reads without
// a sensor option: every sweep becomes the organized CObservation3DRangeScan of docs/formats.md
// §4, rows fitting the real sensor (core::RowRecovery for point clouds, the Ouster metadata's
// beam table for pcaps). Sources: a folder of PCD or KITTI .bin files (dynobj::io::CloudFolder),
// an Ouster pcap + metadata JSON (dynobj::io::OusterPcapReader), a Velodyne pcap
// (dynobj::io::VelodynePcapReader; a pcap without metadata JSON is read as Velodyne). An optional
// poses file becomes one CObservationOdometry (SE(2) part of the pose) before each sweep.
#pragma once

#include <dynobj/core/SensorModel.h>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>

namespace dynobj::mrptio {

struct ImportOptions {
  std::string input;  ///< folder of *.pcd / *.bin, or an Ouster / Velodyne .pcap
  std::string meta;   ///< Ouster metadata JSON (required for an Ouster pcap)
  /// Velodyne pcap: the model (io::VelodyneSensor::fromName); empty = from the packets.
  std::string velodyne_model;
  /// Velodyne pcap: the unit's calibration (Velodyne db.xml, read by MRPT); required for HDL-64E.
  std::string calib;
  std::string dual = "strongest";  ///< Velodyne dual-return captures: "strongest" or "last"
  int data_port = 2368;            ///< Velodyne pcap: UDP port of the data packets
  std::string times;               ///< folder: times file (see io::CloudFolder); empty = `rate`
  std::string poses;  ///< KITTI 3x4 or TUM file, one pose per sweep (or by time for TUM)
  std::optional<core::SensorModel> sensor;  ///< point clouds: rows/cols hint (else recovered)
  std::string sensor_file;                  ///< where `sensor` came from, for messages
  /// With `sensor`: it must fit the data, else the import fails naming both: no sweep may show
  /// more lasers than it has rows, and at most this share of the valid points may fall outside
  /// its vertical field of view.
  double max_outside_fov = 0.05;
  std::string sensor_label = "LIDAR";
  double rate = 10.0;  ///< [Hz] sweep rate of a folder without a times file
};

struct ImportSummary {
  std::size_t sweeps = 0, points = 0, pixels = 0, hidden = 0, outside_fov = 0, invalid = 0;
  std::size_t second_pass = 0;  ///< points of sweeps over 360 degrees scanned a second time
  int rows = 0, cols = 0;
  /// how the rows were found: sweeps per rule ("firing order 153, estimated beam table 1"), or
  /// "metadata beam table"
  std::string rows_from;
  std::string intensity;     ///< the field that became the intensity layer, and its scale
  std::size_t odometry = 0;  ///< CObservationOdometry written
  std::string source;        ///< what was read, for messages
};

/// Called after each sweep with (sweeps done, total or 0 when unknown).
using ImportProgress = std::function<void(std::size_t, std::size_t)>;

/// Reads `o.input` and writes `output` atomically (`<output>.partial`, renamed when complete;
/// removed on any error). Throws io::FormatError / std::runtime_error naming the file and problem.
ImportSummary importRecording(const ImportOptions& o, const std::string& output,
                              const ImportProgress& progress = {});

}  // namespace dynobj::mrptio
