// SPDX-License-Identifier: BSD-3-Clause
// Velodyne data packets -> sweeps (rules in the header).
#include "dynobj/io/VelodyneDecoder.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "dynobj/core/SphericalProjection.h"
#include "dynobj/io/FormatError.h"

namespace dynobj::io {
namespace {

constexpr std::size_t kPacketSize = 1206;
constexpr int kBlocks = 12, kChannels = 32, kBlockSize = 100;
constexpr double kFullTurn = 36000.0;  // [0.01 deg]
constexpr std::size_t kPeriodSamples = 8;

std::uint16_t le16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t le32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) |
         (std::uint32_t{p[3]} << 24);
}
std::string hex(unsigned v, int digits) {
  char buf[16];
  std::snprintf(buf, sizeof(buf), "0x%0*X", digits, v);
  return buf;
}
std::uint16_t blockId(const std::uint8_t* p, int b) {
  return le16(p + b * kBlockSize);
}
std::uint16_t blockAzimuth(const std::uint8_t* p, int b) {
  return le16(p + b * kBlockSize + 2);
}
/// Block id of bank b: 0xEEFF, 0xDDFF, 0xCCFF, 0xBBFF.
std::uint16_t bankId(int b) {
  return static_cast<std::uint16_t>(0xEEFF - 0x1100 * b);
}

/// Banks per firing the block ids show (1, 2 = HDL-64E, 4 = VLS-128), or 0 for another pattern.
int bankLayout(const std::uint8_t* p) {
  for (int banks : {1, 2, 4}) {
    bool fits = true;
    for (int b = 0; b < kBlocks && fits; b++) fits = blockId(p, b) == bankId(b % banks);
    if (fits) return banks;
  }
  return 0;
}

std::string describeProduct(std::uint8_t id) {
  const auto m = VelodyneSensor::fromProductId(id);
  return hex(id, 2) + (m ? " (" + VelodyneSensor::of(*m).name + ")" : "");
}

}  // namespace

VelodyneDecoder::VelodyneDecoder(VelodyneOptions options) : options_(std::move(options)) {}

void VelodyneDecoder::identify(const std::uint8_t* p, std::size_t packet,
                               const std::string& source) {
  const auto fail = [&](const std::string& problem) {
    throwFormatError(source, "packet " + std::to_string(packet) + ": " + problem);
  };
  const int banks = bankLayout(p);
  if (banks == 0)
    for (int b = 0; b < kBlocks; b++)
      if (blockId(p, b) != bankId(0) && blockId(p, b) != bankId(1) && blockId(p, b) != bankId(2) &&
          blockId(p, b) != bankId(3))
        fail("block " + std::to_string(b) + " has id " + hex(blockId(p, b), 4) +
             " (Velodyne data blocks start with 0xEEFF, 0xDDFF, 0xCCFF or 0xBBFF): not a "
             "Velodyne data packet");
  if (banks == 0) fail("block ids in an order no Velodyne model sends");
  mode_byte_ = p[1204];
  product_byte_ = p[1205];
  hdl64_ = banks == 2;
  VelodyneModel model{};
  if (options_.model) {
    model = *options_.model;
    model_source_ = "given";
    if (!hdl64_ && product_byte_ != 0 && VelodyneSensor::fromProductId(product_byte_) != model)
      model_source_ += "; the packets' product id says " + describeProduct(product_byte_);
  } else if (hdl64_) {
    model = VelodyneModel::HDL64E_S3;
    model_source_ = "block ids 0xEEFF/0xDDFF (HDL-64E, S3 timing assumed)";
  } else if (const auto m = VelodyneSensor::fromProductId(product_byte_)) {
    model = *m;
    model_source_ = "product id " + hex(product_byte_, 2);
  } else if (product_byte_ == 0 && banks == 1) {
    model = VelodyneModel::HDL32E;
    model_source_ = "no product id, block ids 0xEEFF only (HDL-32E firmware without factory bytes)";
  } else {
    fail("unknown Velodyne product id " + hex(product_byte_, 2) + " (byte 1205); give the model (" +
         VelodyneSensor::modelNames() + ")");
  }
  sensor_ = VelodyneSensor::of(model);
  if (sensor_.blocks_per_firing != banks)
    fail("the blocks alternate " + std::to_string(banks) + " bank id(s), but a " + sensor_.name +
         " sends " + std::to_string(sensor_.blocks_per_firing) + " (model " + model_source_ + ")");
  if (hdl64_) {
    dual_ = blockAzimuth(p, 0) == blockAzimuth(p, 2);
  } else if (mode_byte_ == 0x39) {
    dual_ = true;
  } else if (mode_byte_ != 0x37 && mode_byte_ != 0x38 && mode_byte_ != 0) {
    fail("unknown return mode byte " + hex(mode_byte_, 2) +
         " (byte 1204; 0x37 strongest, 0x38 last, 0x39 dual)");
  }
  if (dual_ && sensor_.blocks_per_firing > 1)
    fail("dual-return " + sensor_.name +
         " captures are not supported: record in strongest or last return mode");

  elevation_deg_ = sensor_.elevation_deg;
  correction_deg_ = sensor_.azimuth_correction_deg;
  if (!options_.elevation_deg.empty()) {
    if (options_.elevation_deg.size() != static_cast<std::size_t>(sensor_.lasers) ||
        options_.azimuth_correction_deg.size() != options_.elevation_deg.size())
      throwFormatError(options_.calibration_source,
                       "calibration of " + std::to_string(options_.elevation_deg.size()) +
                           " lasers, but the capture is from a " + sensor_.name + " (" +
                           std::to_string(sensor_.lasers) + " lasers)");
    elevation_deg_ = options_.elevation_deg;
    correction_deg_ = options_.azimuth_correction_deg;
  }
  if (elevation_deg_.empty())
    fail(sensor_.name + " beam angles are unit-specific: give the unit's calibration (its db.xml)");
  sensor_.elevation_deg = elevation_deg_;
  sensor_.azimuth_correction_deg = correction_deg_;
  first_layout_ = static_cast<std::uint32_t>(banks);
  identified_ = true;
}

std::int64_t VelodyneDecoder::packetTime(const std::uint8_t* p, std::int64_t capture_time_ns) {
  const std::uint32_t stamp = le32(p + 1200);
  if (!clock_started_) {
    clock_started_ = true;
    clock_ns_ = capture_time_ns;
  } else {
    // Microseconds past the hour: wraps every 3600 s (some firmware counts on to 2^32).
    std::int64_t d = static_cast<std::int64_t>(stamp) - last_stamp_us_;
    if (d < -1800LL * 1000000) d += 3600LL * 1000000;
    const std::int64_t captured_us = (capture_time_ns - last_capture_ns_) / 1000;
    if (d < 0 || std::llabs(d - captured_us) > 1000000) {
      clock_jumps_++;  // the sensor clock jumped (GPS lock, reset): follow the capture clock
      d = std::max<std::int64_t>(captured_us, 0);
    }
    clock_ns_ += d * 1000;
    if (period_samples_us_.size() < kPeriodSamples) period_samples_us_.push_back(double(d));
  }
  last_stamp_us_ = stamp;
  last_capture_ns_ = capture_time_ns;
  return clock_ns_;
}

void VelodyneDecoder::checkPacketPeriod(const std::string& source) {
  if (period_checked_ || period_samples_us_.empty()) return;
  period_checked_ = true;
  std::vector<double> s = period_samples_us_;
  std::nth_element(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(s.size() / 2), s.end());
  const double median = s[s.size() / 2];
  const auto fits = [&](const VelodyneSensor& v) {
    return std::abs(median - v.packetPeriodUs(dual_)) < 0.05 * v.packetPeriodUs(dual_);
  };
  if (median <= 0 || fits(sensor_)) return;
  std::string candidates;
  for (auto m : {VelodyneModel::VLP16, VelodyneModel::PuckHiRes, VelodyneModel::VLP32C,
                 VelodyneModel::HDL32E, VelodyneModel::HDL64E_S2, VelodyneModel::HDL64E_S3,
                 VelodyneModel::VLS128}) {
    const VelodyneSensor v = VelodyneSensor::of(m);
    if (v.blocks_per_firing == sensor_.blocks_per_firing && fits(v))
      candidates += (candidates.empty() ? "" : ", ") + v.name;
  }
  char buf[96];
  std::snprintf(buf, sizeof(buf), "%.1f us of sensor time, but one every %.2f us", median,
                sensor_.packetPeriodUs(dual_));
  throwFormatError(source, "the data packets come every " + std::string(buf) + " comes from the " +
                               sensor_.name + " (model " + model_source_ + ")" +
                               (candidates.empty() ? std::string(" (no supported model fits)")
                                                   : "; models that fit: " + candidates) +
                               ". Give the model explicitly");
}

void VelodyneDecoder::addPacket(const std::uint8_t* data, std::size_t size, std::size_t packet,
                                const std::string& source, std::int64_t capture_time_ns) {
  const auto fail = [&](const std::string& problem) {
    throwFormatError(source, "packet " + std::to_string(packet) + ": " + problem);
  };
  if (data == nullptr || size != kPacketSize)
    fail("data packet of " + std::to_string(size) +
         " bytes; Velodyne data packets are 1206 bytes (truncated, or not a Velodyne capture)");
  if (!identified_) {
    identify(data, packet, source);
    source_ = source;
  }
  const int banks = bankLayout(data);
  if (banks == 0)
    fail("block ids " + hex(blockId(data, 0), 4) + ", " + hex(blockId(data, 1), 4) +
         ", ... are no Velodyne block layout: not a Velodyne data packet");
  if (static_cast<std::uint32_t>(banks) != first_layout_)
    fail("its blocks alternate " + std::to_string(banks) + " bank id(s) (" +
         hex(blockId(data, 0), 4) + ", " + hex(blockId(data, 1), 4) +
         ", ...), but the capture started with " + sensor_.name + " packets (mixed models)");
  if (!hdl64_ && (data[1204] != mode_byte_ || data[1205] != product_byte_))
    fail("product id " + describeProduct(data[1205]) + ", return mode " + hex(data[1204], 2) +
         ", but the capture started with product id " + describeProduct(product_byte_) +
         ", return mode " + hex(mode_byte_, 2) + " (mixed models or modes)");
  const std::int64_t t0 = packetTime(data, capture_time_ns);
  if (period_samples_us_.size() >= kPeriodSamples) checkPacketPeriod(source);

  // Firing groups: the blocks of one firing (x2 in dual-return mode) share one azimuth.
  const int per_group = sensor_.blocks_per_firing * (dual_ ? 2 : 1);
  const int groups = kBlocks / per_group;
  const int fpb = sensor_.firings_per_block;
  double gap = 0;
  for (int g = 0; g < groups; g++) {
    const int b0 = g * per_group;
    // Some units send 36000 for 0.
    const double az = blockAzimuth(data, b0) == 36000 ? 0.0 : blockAzimuth(data, b0);
    if (az > kFullTurn)
      fail("block " + std::to_string(b0) + " has azimuth " + std::to_string(az / 100) +
           " deg (> 360)");
    if (g + 1 < groups) {
      gap = std::fmod(blockAzimuth(data, b0 + per_group) - az + 2 * kFullTurn, kFullTurn);
    }
    // A gap beyond 5 deg is no rotation between two firings: interpolate nothing.
    const double rate = gap > 0 && gap < 500 ? gap / (fpb * sensor_.firing_period_us) : 0.0;
    for (int k = 0; k < fpb; k++) {
      const std::uint8_t* channels[4][2] = {};
      for (int bank = 0; bank < sensor_.blocks_per_firing; bank++)
        for (int r = 0; r < (dual_ ? 2 : 1); r++)
          channels[bank][r] = data + (b0 + bank + r) * kBlockSize + 4 + k * (kChannels / fpb) * 3;
      const std::uint8_t* flat[8];
      for (int i = 0; i < 8; i++) flat[i] = channels[i / 2][i % 2];
      const double firing_az = az + gap * k / fpb;
      const auto firing_index = static_cast<double>(g * fpb + k);
      addFiring(firing_az, rate,
                t0 + std::llround(firing_index * sensor_.firing_period_us * 1000.0),
                capture_time_ns, flat);
    }
  }
}

void VelodyneDecoder::addFiring(double azimuth_cdeg, double rate, std::int64_t time_ns,
                                std::int64_t capture_time_ns, const std::uint8_t* const* channels) {
  if (!firings_.empty() && azimuth_cdeg < last_azimuth_ - kFullTurn / 2) finishSweep();
  last_azimuth_ = azimuth_cdeg;
  firings_.push_back({azimuth_cdeg, rate, time_ns, capture_time_ns, distance_.size()});
  const int per_bank = sensor_.lasers / sensor_.blocks_per_firing;
  for (int l = 0; l < sensor_.lasers; l++) {
    const int bank = l / per_bank, j = l % per_bank;
    const std::uint8_t* a = channels[2 * bank] + 3 * j;  // last (or only) return
    std::uint16_t d = le16(a);
    std::uint8_t i = a[2];
    if (dual_) {
      const std::uint8_t* b = channels[2 * bank + 1] + 3 * j;  // strongest / second strongest
      const std::uint16_t db = le16(b);
      // The sensor repeats a single return in both blocks; a differing second one is dropped.
      const bool differ = db != d || b[2] != i;
      if (differ && (d != 0 || db != 0)) second_returns_++;
      if (options_.dual == DualReturn::Strongest && db != 0 && (d == 0 || b[2] > i)) {
        d = db;
        i = b[2];
      }
    }
    distance_.push_back(d);
    intensity_.push_back(i);
  }
}

void VelodyneDecoder::finishSweep() {
  if (firings_.empty()) return;
  const double span = firings_.back().azimuth_cdeg - firings_.front().azimuth_cdeg;
  if (span < kFullTurn / 2) {
    partial_frames_++;
  } else {
    checkPacketPeriod(source_);
    if (cols_ == 0) {
      const double n = static_cast<double>(firings_.size() - 1);
      cols_ = static_cast<int>(std::lround(kFullTurn * n / span));
      const double dt = static_cast<double>(firings_.back().time_ns - firings_.front().time_ns);
      frequency_hz_ = dt > 0 ? span / kFullTurn / (dt * 1e-9) : 10.0;
      laser_row_ = sensorModel().laserToRow();
    }
    VelodyneScan scan;
    buildScan(scan);
    done_.push_back(std::move(scan));
  }
  firings_.clear();
  distance_.clear();
  intensity_.clear();
}

core::SensorModel VelodyneDecoder::sensorModel() const {
  return sensor_.sensorModel(cols_, frequency_hz_);
}

void VelodyneDecoder::buildScan(VelodyneScan& scan) const {
  const core::SphericalProjection eq1(sensorModel());
  const double deg = M_PI / 180.0;
  const Firing& first = firings_.front();
  scan.timestamp_ns = first.time_ns;
  scan.capture_time_ns = first.capture_time_ns;
  scan.firings = static_cast<int>(firings_.size());
  scan.azimuth_span_deg = (firings_.back().azimuth_cdeg - first.azimuth_cdeg) / 100.0;
  const double a0 = first.azimuth_cdeg / 100.0 * deg;
  const int c0 = eq1.columnOf(std::cos(a0), -std::sin(a0));
  const double cols_per_cdeg = cols_ / kFullTurn;
  const auto n_lasers = static_cast<std::size_t>(sensor_.lasers);
  std::vector<int> shift(n_lasers);
  std::vector<double> sin_e(n_lasers), cos_e(n_lasers);
  for (std::size_t l = 0; l < n_lasers; l++) {
    shift[l] = static_cast<int>(std::lround(correction_deg_[l] * 100 * cols_per_cdeg));
    sin_e[l] = std::sin(elevation_deg_[l] * deg);
    cos_e[l] = std::cos(elevation_deg_[l] * deg);
  }
  core::PointCloud& cloud = scan.cloud;
  const std::size_t returns = static_cast<std::size_t>(
      std::count_if(distance_.begin(), distance_.end(), [](std::uint16_t d) { return d != 0; }));
  cloud.reserve(returns, true, true);
  cloud.ring.reserve(returns);
  scan.time_ns.reserve(returns);
  scan.azimuth_deg.reserve(returns);
  scan.no_return = distance_.size() - returns;
  for (const Firing& f : firings_) {
    const int fc =
        c0 - static_cast<int>(std::lround((f.azimuth_cdeg - first.azimuth_cdeg) * cols_per_cdeg));
    for (std::size_t l = 0; l < n_lasers; l++) {
      const std::uint16_t d = distance_[f.first + l];
      if (d == 0) continue;
      const double dt_us = sensor_.laser_time_us[l];
      const double a_cdeg = f.azimuth_cdeg + f.rate_cdeg_per_us * dt_us - correction_deg_[l] * 100;
      const double a = std::fmod(a_cdeg / 100.0 + 720.0, 360.0);
      const double r = d * sensor_.distance_unit_m;
      const double xy = r * cos_e[l];
      const int col = ((fc + shift[l]) % cols_ + cols_) % cols_;
      cloud.push_back(static_cast<float>(xy * std::cos(a * deg)),
                      static_cast<float>(-xy * std::sin(a * deg)), static_cast<float>(r * sin_e[l]),
                      intensity_[f.first + l], static_cast<std::uint16_t>(laser_row_[l]),
                      static_cast<std::uint16_t>(col));
      cloud.ring.push_back(static_cast<std::uint16_t>(l));
      scan.time_ns.push_back(
          static_cast<std::int32_t>(f.time_ns - first.time_ns + std::llround(dt_us * 1000.0)));
      scan.azimuth_deg.push_back(static_cast<float>(a));
    }
  }
}

void VelodyneDecoder::flush(const std::string& source) {
  checkPacketPeriod(source);
  finishSweep();
}

bool VelodyneDecoder::popFrame(VelodyneScan& scan) {
  if (done_.empty()) return false;
  scan = std::move(done_.front());
  done_.pop_front();
  return true;
}

}  // namespace dynobj::io
