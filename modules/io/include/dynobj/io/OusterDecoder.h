// SPDX-License-Identifier: BSD-3-Clause
// Ouster lidar UDP payloads -> frames: per-column decoding of the three single-return packet
// profiles, grouping of columns into frames, destaggering, and the organized point cloud
// (the SDK's xyz look-up table: beam origin offset, encoder angle, beam azimuth offset,
// lidar_to_sensor transform). Packet layouts: ../shared/notes/lidar-intensity-facts.md.
//
// Frames: a new frame starts when the frame_id changes (the packet header's for FW >= 2.2
// profiles, the column header's for LEGACY) or, for LEGACY, when the measurement id wraps
// around within one frame_id. A column counts when its status bit 0 is set (LEGACY sends
// 0xFFFFFFFF); others stay empty (range 0). A frame with fewer valid columns than half the
// column window (the first / last frame of a capture) is dropped and counted.
// Errors (FormatError "<source>: packet N: ..."): a payload whose size differs from the
// metadata's, a valid column whose measurement id is >= columns_per_frame, a packet whose
// serial number differs from the metadata's prod_sn (metadata of another sensor). An
// initialization id that differs from the metadata's (sensor re-initialised) is only counted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "dynobj/core/PointCloud.h"
#include "dynobj/io/OusterMetadata.h"

namespace dynobj::io {

struct OusterScan {
  /// Sensor timestamp of the lowest valid measurement id [ns]: the sensor's clock (time since
  /// power-on unless the sensor is PTP / GPS synchronised).
  std::int64_t timestamp_ns = 0;
  /// pcap capture time of the packet that started the frame [ns since the Unix epoch].
  std::int64_t capture_time_ns = 0;
  std::uint32_t frame_id = 0;
  int columns_valid = 0;  ///< columns with valid status received in this frame
  /// Organized: one point per pixel with a return (range != 0), rows top to bottom, columns
  /// in the Eq. (1) layout (col = OusterMetadata::eq1Column(destaggered column)); x, y, z in
  /// the sensor frame [m]; intensity = signal if the profile has it, else reflectivity.
  core::PointCloud cloud;
  std::string intensity_field;  ///< "signal" or "reflectivity"
  /// H x W images in the SDK's destaggered layout (not the Eq. (1) one), 0 = no return.
  /// Range in mm; int32 because OpenCV 4 has no uint32 matrices (ranges are < 2^20).
  cv::Mat_<std::int32_t> range_mm;
  /// Destaggered; empty when the profile lacks the field. RNG15_RFL8_NIR8 near-IR is scaled
  /// x16 as in the SDK; LEGACY reflectivity is 16-bit on FW 2.0/2.1.
  cv::Mat_<std::uint16_t> signal, reflectivity, near_ir;
};

class OusterDecoder {
 public:
  /// `meta` must come from OusterMetadata::load (validated).
  explicit OusterDecoder(const OusterMetadata& meta);

  /// Decodes one lidar UDP payload. `packet` (1-based record number) and `source` name it in
  /// errors. Frames it completes are queued for popFrame().
  void addPacket(const std::uint8_t* data, std::size_t size, std::size_t packet,
                 const std::string& source, std::int64_t capture_time_ns = 0);
  /// Ends the frame in progress (end of the capture).
  void flush();
  /// Oldest completed full frame; false if none is queued.
  bool popFrame(OusterScan& scan);

  std::size_t partialFramesSkipped() const { return partial_frames_; }
  std::size_t initIdMismatches() const { return init_id_mismatches_; }
  const OusterMetadata& metadata() const { return meta_; }

 private:
  struct Column {
    std::int64_t timestamp_ns;
    std::uint32_t measurement_id, frame_id;
    bool valid;
  };
  void startFrame(std::uint32_t frame_id, std::int64_t capture_time_ns);
  void finishFrame();
  void addColumn(const std::uint8_t* col, const Column& c);
  void buildCloud(OusterScan& scan) const;

  OusterMetadata meta_;
  int h_ = 0, w_ = 0;
  int eq1_base_ = 0;
  std::vector<double> lut_dir_, lut_off_;  ///< per staggered pixel (u * W + m): x, y, z
  bool in_frame_ = false;
  std::uint32_t last_mid_ = 0;      ///< measurement id of the previous valid column
  std::uint32_t min_mid_ = 0;       ///< lowest measurement id of the frame in progress
  std::vector<std::uint8_t> seen_;  ///< per measurement id of the frame in progress
  OusterScan current_;
  std::deque<OusterScan> done_;
  std::size_t partial_frames_ = 0, init_id_mismatches_ = 0;
};

}  // namespace dynobj::io
