// SPDX-License-Identifier: BSD-3-Clause
// Velodyne data packets (1206-byte UDP payloads) -> sweeps: the model from the packets' factory
// bytes (or given), firings decoded with the model's beam table and firing timing
// (VelodyneSensor), sweeps split where the azimuth wraps around (one sweep = 360 deg), and the
// organized cloud of each sweep.
//
// Packet: 12 blocks of 100 bytes (block id, azimuth in 0.01 deg, 32 x (distance uint16,
// intensity uint8)), then the sensor timestamp (us, uint32), the return mode byte 1204 (0x37
// strongest, 0x38 last, 0x39 dual) and the product id byte 1205, little-endian. HDL-64E packets
// alternate upper (0xEEFF) and lower (0xDDFF) blocks and carry status bytes where the others
// carry the factory bytes; VLS-128 packets cycle through four banks (0xEEFF .. 0xBBFF).
//
// Model: `model` if given, else the product id, else (no product id) the block ids: upper/lower
// -> HDL-64E (S3 timing; give hdl-64e-s2 for an S2), 0xEEFF only -> HDL-32E (its older firmware
// sends no factory bytes). The packet period (sensor time between packets) must fit the model:
// a capture whose factory byte names another model (the VeloView VLP-16 sample says HDL-32E) is
// refused, naming the models whose timing fits.
// Geometry: point of laser l at distance d, sensor azimuth a (0.01 deg, clockwise from +X) and
// elevation w: x = d cos w cos a, y = -d cos w sin a, z = d sin w (+X forward, +Y left, as MRPT
// and ROS drivers); a = block azimuth + the rotation during the laser's firing delay
// (interpolated to the next firing's azimuth) - the laser's azimuth correction.
// Dual returns (VLP-16, Puck Hi-Res, HDL-32E, VLP-32C: two blocks per firing, last then
// strongest / second strongest): one return per laser is kept, `dual` says which; the other is
// counted. HDL-64E and VLS-128 dual-return captures are refused.
// Sweeps: a new sweep starts when a firing's azimuth is below the previous one by more than
// 180 deg. A sweep covering less than 180 deg (the first and last of a capture) is dropped and
// counted. Columns: the first kept sweep sets the column count (firings per revolution, from its
// firings and azimuth span) and the frequency; a firing's column is the Eq. (1) column of its
// azimuth (counter-clockwise from -pi, as every dynobj frame), a laser's column that plus its
// azimuth correction in columns; rows are lasers ordered by elevation.
// Errors (FormatError "<source>: packet N: ..."): a payload that is not 1206 bytes, an unknown
// block id, an unknown product id or return mode (without `model`), a packet whose factory
// bytes or block layout differ from the first packet's (mixed models), a packet period that does
// not fit the model, a calibration whose laser count differs, HDL-64E without a calibration.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/core/PointCloud.h"
#include "dynobj/core/SensorModel.h"
#include "dynobj/io/VelodyneSensor.h"

namespace dynobj::io {

/// Which return of a dual-return firing becomes the point.
enum class DualReturn { Strongest, Last };

struct VelodyneOptions {
  std::optional<VelodyneModel> model;  ///< nullopt: from the packets
  /// A unit calibration (laser-id order) replacing the model's nominal table: elevation and
  /// azimuth correction (rotCorrection sign) [deg]. Required for HDL-64E.
  std::vector<double> elevation_deg, azimuth_correction_deg;
  std::string calibration_source;  ///< where it came from, for messages
  DualReturn dual = DualReturn::Strongest;
};

struct VelodyneScan {
  /// Time of the sweep's first firing [ns since the Unix epoch]: the sensor's clock (packet
  /// timestamps), anchored to the pcap capture time of the capture's first data packet.
  std::int64_t timestamp_ns = 0;
  std::int64_t capture_time_ns = 0;  ///< pcap time of the packet holding the first firing
  int firings = 0;                   ///< firings (columns) in the sweep
  double azimuth_span_deg = 0;       ///< from the first to the last firing
  /// Organized: one point per return (distance != 0); row = laser's row by elevation (0 = top),
  /// col as in the header; ring = laser id; intensity 0-255.
  core::PointCloud cloud;
  std::vector<std::int32_t> time_ns;  ///< per point: firing time - timestamp_ns [ns]
  std::vector<float> azimuth_deg;     ///< per point: the sensor azimuth a of the header [deg]
  std::size_t no_return = 0;          ///< laser firings without a return (distance 0)
};

class VelodyneDecoder {
 public:
  explicit VelodyneDecoder(VelodyneOptions options = {});

  /// Decodes one data packet (UDP payload). `packet` (1-based record number) and `source` name
  /// it in errors; `capture_time_ns` is its pcap time. Sweeps it completes are queued.
  void addPacket(const std::uint8_t* data, std::size_t size, std::size_t packet,
                 const std::string& source, std::int64_t capture_time_ns);
  /// Ends the sweep in progress (end of the capture).
  void flush(const std::string& source);
  /// Oldest completed sweep; false if none is queued.
  bool popFrame(VelodyneScan& scan);

  bool identified() const { return identified_; }
  const VelodyneSensor& sensor() const { return sensor_; }
  /// How the model was identified, e.g. "product id 0x21", "given", "block ids".
  const std::string& modelSource() const { return model_source_; }
  bool dualReturn() const { return dual_; }
  /// Set once the first sweep was kept; 0 before.
  int cols() const { return cols_; }
  double frequencyHz() const { return frequency_hz_; }
  /// The sensor model of the frames (rows, cols, beam table); valid once cols() > 0.
  core::SensorModel sensorModel() const;

  std::size_t partialFramesSkipped() const { return partial_frames_; }
  std::size_t secondReturnsDropped() const { return second_returns_; }
  std::size_t clockJumps() const { return clock_jumps_; }

 private:
  struct Firing {
    double azimuth_cdeg;      ///< [0.01 deg] azimuth of the firing (unwrapped within a sweep)
    double rate_cdeg_per_us;  ///< rotation speed around it
    std::int64_t time_ns;     ///< time of the firing's first laser
    std::int64_t capture_time_ns;
    std::size_t first;  ///< index of its first laser in distance_/intensity_
  };
  void identify(const std::uint8_t* p, std::size_t packet, const std::string& source);
  void checkPacketPeriod(const std::string& source);
  std::int64_t packetTime(const std::uint8_t* p, std::int64_t capture_time_ns);
  void addFiring(double azimuth_cdeg, double rate, std::int64_t time_ns,
                 std::int64_t capture_time_ns, const std::uint8_t* const* channels);
  void finishSweep();
  void buildScan(VelodyneScan& scan) const;

  VelodyneOptions options_;
  VelodyneSensor sensor_;
  std::vector<double> elevation_deg_, correction_deg_;
  std::vector<int> laser_row_;
  bool identified_ = false, dual_ = false, hdl64_ = false;
  std::string model_source_, source_;
  std::uint8_t mode_byte_ = 0, product_byte_ = 0;
  std::uint32_t first_layout_ = 0;  ///< block-id signature of the first packet

  // Clock: the sensor's timestamps, anchored to the first packet's capture time.
  bool clock_started_ = false;
  std::uint32_t last_stamp_us_ = 0;
  std::int64_t last_capture_ns_ = 0, clock_ns_ = 0;
  std::vector<double> period_samples_us_;
  bool period_checked_ = false;
  std::size_t clock_jumps_ = 0;

  // The sweep in progress.
  std::vector<Firing> firings_;
  std::vector<std::uint16_t> distance_;
  std::vector<std::uint8_t> intensity_;
  double last_azimuth_ = -1;

  int cols_ = 0;
  double frequency_hz_ = 0;
  std::deque<VelodyneScan> done_;
  std::size_t partial_frames_ = 0, second_returns_ = 0;
};

}  // namespace dynobj::io
