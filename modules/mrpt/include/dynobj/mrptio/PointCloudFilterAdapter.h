// SPDX-License-Identifier: BSD-3-Clause
// The detector behind MRPT's own dynamic-point interface, mrpt::maps::CPointCloudFilterBase, so any
// MRPT code that takes such a filter (e.g. in place of CPointCloudFilterByDistance) can use it.
// Each call is one LiDAR sweep: the cloud in the sensor frame, its pose in the world (which gives
// the ego-motion between calls), and a sensor model to organize it (Eq. 1).
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <mrpt/maps/CPointCloudFilterBase.h>
#include <mrpt/poses/CPose3D.h>

#include <optional>

namespace dynobj::mrptio {

class PointCloudFilterAdapter : public mrpt::maps::CPointCloudFilterBase {
 public:
  PointCloudFilterAdapter(const core::SensorModel& sensor, const core::DetectorParams& params = {});

  /// Marks (in params->out_deletion_mask) and, unless params->do_not_delete, deletes the
  /// dynamic points of `cloud` (sensor frame; `pose` = sensor pose in the world).
  void filter(mrpt::maps::CPointsMap* cloud, const mrpt::system::TTimeStamp stamp,
              const mrpt::poses::CPose3D& pose, TExtraFilterParams* params = nullptr) override;

  const core::DetectionResult& lastResult() const { return *last_; }

 private:
  core::SensorModel sensor_;
  core::DynamicObjectDetector detector_;
  std::optional<mrpt::poses::CPose3D> prev_pose_;
  const core::DetectionResult* last_ = nullptr;
};

}  // namespace dynobj::mrptio
