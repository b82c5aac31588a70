// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/KthExport.h"

#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "dynobj/mapclean/MapCleaner.h"

namespace dynobj::mapclean {

namespace fs = std::filesystem;

KthExporter::KthExporter(std::string dir, bool with_ground_truth, bool replace)
    : dir_(std::move(dir)), partial_(io::partialName(dir_)), replace_(replace) {
  if (fs::exists(dir_) && !replace_)
    throw std::runtime_error("export folder '" + dir_ + "' exists (use -w to replace it)");
  std::error_code ec;
  fs::remove_all(partial_, ec);
  fs::create_directories(fs::path(partial_) / "pcd", ec);
  if (ec) throw std::runtime_error("cannot create '" + partial_ + "/pcd': " + ec.message());
  if (with_ground_truth) gt_ = std::make_unique<PcdStreamWriter>(partial_ + "/gt_cloud.pcd");
}

KthExporter::~KthExporter() {
  if (closed_) return;
  gt_.reset();
  std::error_code ec;
  fs::remove_all(partial_, ec);
}

void KthExporter::add(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose,
                      const cv::Mat_<std::uint8_t>* gt_dynamic) {
  if (gt_ && !gt_dynamic) throw std::logic_error("KthExporter: ground truth missing for a frame");
  std::vector<MapPoint> pts;
  pts.reserve(frame.validCount());
  forEachWorldPoint(frame, sensor_pose, 0.0, [&](int r, int c, const MapPoint& p) {
    pts.push_back(p);
    if (gt_) gt_->add({p.x, p.y, p.z, (*gt_dynamic)(r, c) ? 1.f : 0.f});
  });
  char name[32];
  std::snprintf(name, sizeof(name), "/pcd/%06zu.pcd", frames_);
  writePcd(partial_ + name, pts, sensor_pose, "timestamp_ns " + std::to_string(frame.timestamp_ns));
  frames_++;
  points_ += pts.size();
}

void KthExporter::close() {
  if (gt_) gt_->close();
  gt_.reset();
  std::error_code ec;
  if (replace_) fs::remove_all(dir_, ec);
  fs::rename(partial_, dir_, ec);
  if (ec)
    throw std::runtime_error("cannot rename '" + partial_ + "' to '" + dir_ + "': " + ec.message());
  closed_ = true;
}

}  // namespace dynobj::mapclean
