// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/PointCloudFilterAdapter.h"

#include <dynobj/core/SphericalProjection.h>
#include <mrpt/maps/CPointsMap.h>

#include "dynobj/mrptio/PoseConversion.h"
#include "dynobj/mrptio/TimeConversion.h"

namespace dynobj::mrptio {

PointCloudFilterAdapter::PointCloudFilterAdapter(const core::SensorModel& sensor,
                                                 const core::DetectorParams& params)
    : sensor_(sensor), detector_(params) {
  sensor_.validate();
}

void PointCloudFilterAdapter::filter(mrpt::maps::CPointsMap* cloud,
                                     const mrpt::system::TTimeStamp stamp,
                                     const mrpt::poses::CPose3D& pose, TExtraFilterParams* params) {
  if (!cloud) throw std::invalid_argument("PointCloudFilterAdapter::filter: null point cloud");
  core::PointCloud pc;
  const auto& xs = cloud->getPointsBufferRef_x();
  const auto& ys = cloud->getPointsBufferRef_y();
  const auto& zs = cloud->getPointsBufferRef_z();
  pc.x.assign(xs.begin(), xs.end());
  pc.y.assign(ys.begin(), ys.end());
  pc.z.assign(zs.begin(), zs.end());
  core::LidarFrame frame;
  core::SphericalProjection(sensor_).project(pc, frame);  // Eq. (1); no intensity: range is used
  frame.timestamp_ns = toUnixNs(stamp);
  std::optional<Eigen::Isometry3d> motion;  // T_{prev<-cur} from the given poses
  if (prev_pose_) {
    // `a - b` in MRPT is a expressed in b's frame: the current pose seen from the previous one.
    motion = toIsometry(pose - *prev_pose_);
  }
  prev_pose_ = pose;
  last_ = &detector_.process(frame, motion);
  const std::vector<std::uint8_t> mask = frame.pointMaskFromPixelMask(last_->dynamic);
  std::vector<bool> del(mask.begin(), mask.end());
  if (params && params->out_deletion_mask) *params->out_deletion_mask = del;
  if (!params || !params->do_not_delete) cloud->applyDeletionMask(del);
}

}  // namespace dynobj::mrptio
