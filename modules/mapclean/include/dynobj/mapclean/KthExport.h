// SPDX-License-Identifier: BSD-3-Clause
// Export in the KTH DynamicMap benchmark layout (MRPT-free):
//   <dir>/pcd/000000.pcd ...  binary PCD per scan, x y z intensity in the WORLD frame,
//                             VIEWPOINT = sensor pose, "# timestamp_ns <t>" comment line;
//   <dir>/gt_cloud.pcd        every point of every scan, intensity 0 = static, 1 = dynamic
//                             (only with ground truth).
// Written into "<dir>.partial" and renamed at close(); an existing <dir> is an error.
#pragma once

#include <dynobj/core/LidarFrame.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "dynobj/mapclean/PointCloudIO.h"

namespace dynobj::mapclean {

class KthExporter {
 public:
  /// An existing `dir` is an error, unless `replace`: then close() replaces it.
  KthExporter(std::string dir, bool with_ground_truth, bool replace = false);
  ~KthExporter();
  KthExporter(const KthExporter&) = delete;
  KthExporter& operator=(const KthExporter&) = delete;

  /// One scan: its valid pixels in the world. `gt_dynamic` (H x W, non-zero = dynamic) is
  /// required when exporting ground truth.
  void add(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose,
           const cv::Mat_<std::uint8_t>* gt_dynamic = nullptr);
  std::size_t frames() const { return frames_; }
  std::size_t points() const { return points_; }
  void close();

 private:
  std::string dir_, partial_;
  std::unique_ptr<PcdStreamWriter> gt_;
  std::size_t frames_ = 0, points_ = 0;
  bool closed_ = false;
  bool replace_ = false;
};

}  // namespace dynobj::mapclean
