// SPDX-License-Identifier: BSD-3-Clause
// Ouster lidar packets -> destaggered images and the organized cloud (rules in the header).
#include "dynobj/io/OusterDecoder.h"

#include <Eigen/Geometry>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dynobj/io/FormatError.h"

namespace dynobj::io {
namespace {

enum Profile { kLegacy, kSingle, kLowBandwidth };

std::uint16_t le16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t le32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) |
         (std::uint32_t{p[3]} << 24);
}
std::uint64_t leN(const std::uint8_t* p, int n) {
  std::uint64_t v = 0;
  for (int i = n - 1; i >= 0; i--) v = (v << 8) | p[i];
  return v;
}

Profile profileOf(const std::string& name) {
  if (name == "LEGACY") return kLegacy;
  if (name == "RNG15_RFL8_NIR8") return kLowBandwidth;
  return kSingle;
}

}  // namespace

OusterDecoder::OusterDecoder(const OusterMetadata& meta)
    : meta_(meta), h_(meta.rows), w_(meta.cols), eq1_base_(meta.eq1ColumnBase()) {
  const auto h = static_cast<std::size_t>(h_);
  if (h_ < 1 || w_ < 1 || meta.pixel_shift_by_row.size() != h ||
      meta.beam_altitude_deg.size() != h || meta.beam_azimuth_deg.size() != h)
    throw std::invalid_argument("OusterDecoder: metadata not validated (use OusterMetadata::load)");
  for (int s : meta.pixel_shift_by_row)
    if (s < 0 || s >= w_) throw std::invalid_argument("OusterDecoder: pixel shift out of range");

  // The SDK's xyz look-up table, per staggered pixel (row u, measurement id m).
  const Eigen::Matrix3d rot = meta.lidar_to_sensor.topLeftCorner<3, 3>();
  const Eigen::Vector3d trans = meta.lidar_to_sensor.topRightCorner<3, 1>();
  const double n = meta.lidar_origin_to_beam_origin_mm;
  const std::size_t npix = h * static_cast<std::size_t>(w_);
  lut_dir_.resize(3 * npix);
  lut_off_.resize(3 * npix);
  for (int u = 0; u < h_; u++) {
    const double azimuth = -meta.beam_azimuth_deg[static_cast<std::size_t>(u)] * M_PI / 180;
    const double altitude = meta.beam_altitude_deg[static_cast<std::size_t>(u)] * M_PI / 180;
    for (int m = 0; m < w_; m++) {
      const double encoder = 2 * M_PI * (1.0 - static_cast<double>(m) / w_);
      const Eigen::Vector3d dir(std::cos(encoder + azimuth) * std::cos(altitude),
                                std::sin(encoder + azimuth) * std::cos(altitude),
                                std::sin(altitude));
      const Eigen::Vector3d off(n * std::cos(encoder) - n * dir.x(),
                                n * std::sin(encoder) - n * dir.y(),
                                -n * dir.z() + meta.beam_origin_z_mm);
      const Eigen::Vector3d d = rot * dir * 1e-3;  // [m per mm of range]
      const Eigen::Vector3d o = (rot * off + trans) * 1e-3;
      const std::size_t i = 3 * (static_cast<std::size_t>(u) * static_cast<std::size_t>(w_) +
                                 static_cast<std::size_t>(m));
      for (int k = 0; k < 3; k++) {
        lut_dir_[i + static_cast<std::size_t>(k)] = d[k];
        lut_off_[i + static_cast<std::size_t>(k)] = o[k];
      }
    }
  }
}

void OusterDecoder::addPacket(const std::uint8_t* data, std::size_t size, std::size_t packet,
                              const std::string& source, std::int64_t capture_time_ns) {
  const auto fail = [&](const std::string& problem) {
    throwFormatError(source, "packet " + std::to_string(packet) + ": " + problem);
  };
  const std::size_t expected = meta_.lidarPacketSize();
  if (size != expected || data == nullptr)
    fail("lidar packet of " + std::to_string(size) + " bytes, but profile " + meta_.profile +
         " with " + std::to_string(h_) + " rows and " + std::to_string(meta_.columns_per_packet) +
         " columns per packet expects " + std::to_string(expected) +
         " bytes (metadata of another sensor or mode?)");
  const Profile profile = profileOf(meta_.profile);
  const auto h = static_cast<std::size_t>(h_);
  std::size_t first = 0, block = 0;
  std::uint32_t packet_frame = 0;
  if (profile == kLegacy) {
    block = 16 + h * 12 + 4;
  } else {
    first = 32;
    block = 12 + h * (profile == kLowBandwidth ? 4 : 12);
    packet_frame = le16(data + 2);
    const std::uint64_t serial = leN(data + 7, 5);
    if (meta_.serial_number != 0 && serial != meta_.serial_number)
      fail("sensor serial number " + std::to_string(serial) + " but the metadata's prod_sn is " +
           std::to_string(meta_.serial_number) + " (metadata of another sensor)");
    if (meta_.initialization_id != 0 && leN(data + 4, 3) != meta_.initialization_id)
      init_id_mismatches_++;
  }
  for (int k = 0; k < meta_.columns_per_packet; k++) {
    const std::uint8_t* b = data + first + static_cast<std::size_t>(k) * block;
    Column c{static_cast<std::int64_t>(leN(b, 8)), le16(b + 8), packet_frame, false};
    if (profile == kLegacy) {
      c.frame_id = le16(b + 10);
      c.valid = (le32(b + block - 4) & 1u) != 0;
    } else {
      c.valid = (le16(b + 10) & 1u) != 0;
    }
    if (!c.valid) continue;
    if (c.measurement_id >= static_cast<std::uint32_t>(w_))
      fail("column " + std::to_string(k) + " has measurement id " +
           std::to_string(c.measurement_id) + " >= columns_per_frame " + std::to_string(w_));
    const bool wrapped =
        profile == kLegacy && c.measurement_id + static_cast<std::uint32_t>(w_ / 2) < last_mid_;
    if (!in_frame_ || c.frame_id != current_.frame_id || wrapped) {
      if (in_frame_) finishFrame();
      startFrame(c.frame_id, capture_time_ns);
    }
    addColumn(b + (profile == kLegacy ? 16 : 12), c);
  }
}

void OusterDecoder::startFrame(std::uint32_t frame_id, std::int64_t capture_time_ns) {
  current_ = OusterScan{};
  current_.frame_id = frame_id;
  current_.capture_time_ns = capture_time_ns;
  current_.intensity_field = meta_.hasSignal() ? "signal" : "reflectivity";
  current_.range_mm = cv::Mat_<std::int32_t>::zeros(h_, w_);
  current_.reflectivity = cv::Mat_<std::uint16_t>::zeros(h_, w_);
  current_.near_ir = cv::Mat_<std::uint16_t>::zeros(h_, w_);
  if (meta_.hasSignal()) current_.signal = cv::Mat_<std::uint16_t>::zeros(h_, w_);
  seen_.assign(static_cast<std::size_t>(w_), 0);
  min_mid_ = std::numeric_limits<std::uint32_t>::max();
  in_frame_ = true;
}

void OusterDecoder::addColumn(const std::uint8_t* pix, const Column& c) {
  const std::uint32_t mid = c.measurement_id;
  if (!seen_[mid]) {
    seen_[mid] = 1;
    current_.columns_valid++;
  }
  if (mid < min_mid_) {
    min_mid_ = mid;
    current_.timestamp_ns = c.timestamp_ns;
  }
  last_mid_ = mid;
  const Profile profile = profileOf(meta_.profile);
  const std::size_t pixel_size = profile == kLowBandwidth ? 4 : 12;
  for (int u = 0; u < h_; u++) {
    const std::uint8_t* p = pix + static_cast<std::size_t>(u) * pixel_size;
    const int col =
        (static_cast<int>(mid) + meta_.pixel_shift_by_row[static_cast<std::size_t>(u)]) % w_;
    if (profile == kLegacy) {
      current_.range_mm(u, col) = static_cast<std::int32_t>(le32(p) & 0xFFFFFu);
      current_.reflectivity(u, col) = le16(p + 4);
      current_.signal(u, col) = le16(p + 6);
      current_.near_ir(u, col) = le16(p + 8);
    } else if (profile == kSingle) {
      current_.range_mm(u, col) = static_cast<std::int32_t>(le32(p) & 0x7FFFFu);
      current_.reflectivity(u, col) = p[4];
      current_.signal(u, col) = le16(p + 6);
      current_.near_ir(u, col) = le16(p + 8);
    } else {
      current_.range_mm(u, col) = (le16(p) & 0x7FFF) * 8;
      current_.reflectivity(u, col) = p[2];
      current_.near_ir(u, col) = static_cast<std::uint16_t>(p[3] * 16);
    }
  }
}

void OusterDecoder::finishFrame() {
  in_frame_ = false;
  if (2 * current_.columns_valid < meta_.columnWindowWidth()) {
    partial_frames_++;
    return;
  }
  buildCloud(current_);
  done_.push_back(std::move(current_));
  current_ = OusterScan{};
}

void OusterDecoder::flush() {
  if (in_frame_) finishFrame();
}

bool OusterDecoder::popFrame(OusterScan& scan) {
  if (done_.empty()) return false;
  scan = std::move(done_.front());
  done_.pop_front();
  return true;
}

void OusterDecoder::buildCloud(OusterScan& scan) const {
  core::PointCloud& cloud = scan.cloud;
  cloud.clear();
  cloud.reserve(static_cast<std::size_t>(cv::countNonZero(scan.range_mm != 0)), true, true);
  const bool use_signal = meta_.hasSignal();
  for (int u = 0; u < h_; u++) {
    const int shift = meta_.pixel_shift_by_row[static_cast<std::size_t>(u)];
    for (int k = 0; k < w_; k++) {
      const int c = ((eq1_base_ - k) % w_ + w_) % w_;  // destaggered column shown at Eq. (1) k
      const std::int32_t r = scan.range_mm(u, c);
      if (r <= 0) continue;
      const int m = (c - shift + w_) % w_;  // measurement id = staggered column
      const std::size_t i = 3 * (static_cast<std::size_t>(u) * static_cast<std::size_t>(w_) +
                                 static_cast<std::size_t>(m));
      const double rr = r;
      const float intensity = use_signal ? scan.signal(u, c) : scan.reflectivity(u, c);
      cloud.push_back(static_cast<float>(lut_dir_[i] * rr + lut_off_[i]),
                      static_cast<float>(lut_dir_[i + 1] * rr + lut_off_[i + 1]),
                      static_cast<float>(lut_dir_[i + 2] * rr + lut_off_[i + 2]), intensity,
                      static_cast<std::uint16_t>(u), static_cast<std::uint16_t>(k));
    }
  }
}

}  // namespace dynobj::io
