// SPDX-License-Identifier: BSD-3-Clause
// The one rule for recordings with several LiDARs: every sensor label is a sequence of its own,
// with its own detector (tracks, windows, ego-motion state), created at its first frame. Used by
// SequenceRunner (offline tools) and DynamicObjectFilter (per observation, inside MRPT chains).
// Outputs that hold one sensor only (label files, ground truth, maps) ask for one label instead
// (SequenceOptions::single_sensor, --sensor-label).
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

namespace dynobj::mrptio {

class DetectorBank {
 public:
  /// Validates `params` (throws core::ParameterError naming the bad key).
  explicit DetectorBank(core::DetectorParams params);

  /// The detector of this sensor label (created on first use).
  core::DynamicObjectDetector& detector(const std::string& sensor_label);
  /// detector(sensor_label).process(frame, motion).
  const core::DetectionResult& process(const std::string& sensor_label,
                                       const core::LidarFrame& frame,
                                       const std::optional<Eigen::Isometry3d>& motion = {}) {
    return detector(sensor_label).process(frame, motion);
  }

  std::size_t sensors() const { return detectors_.size(); }
  const core::DetectorParams& params() const { return params_; }

 private:
  core::DetectorParams params_;
  std::map<std::string, std::unique_ptr<core::DynamicObjectDetector>> detectors_;
};

}  // namespace dynobj::mrptio
