// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/label/SweepSource.h"

#include <dynobj/mrptio/RawlogIndex.h>

namespace dynobj::label {

void MemorySweeps::add(core::LidarFrame frame, std::optional<Eigen::Isometry3d> pose) {
  frames_.push_back(std::move(frame));
  poses_.push_back(pose);
}

void MemorySweeps::load(std::size_t k, core::LidarFrame& frame,
                        std::optional<Eigen::Isometry3d>& pose) {
  const core::LidarFrame& f = frames_.at(k);
  frame.sensor = f.sensor;
  frame.timestamp_ns = f.timestamp_ns;
  frame.has_intensity = f.has_intensity;
  frame.range = f.range.clone();
  frame.intensity = f.intensity.clone();
  frame.xyz = f.xyz.clone();
  frame.valid = f.valid.clone();
  frame.source_index = f.source_index.clone();
  frame.point_pixel = f.point_pixel;
  pose = poses_.at(k);
}

RawlogSweeps::RawlogSweeps(const std::string& rawlog, const mrptio::ObservationConverter& converter,
                           const std::string& sensor_label,
                           std::function<void(std::size_t, std::uint64_t)> progress)
    : index_(std::make_unique<mrptio::RawlogIndex>(
          rawlog, converter,
          mrptio::RawlogIndex::Options{sensor_label, std::move(progress), 32ull << 20})) {}

RawlogSweeps::~RawlogSweeps() = default;

std::size_t RawlogSweeps::size() const {
  return index_->size();
}

std::int64_t RawlogSweeps::timestamp(std::size_t k) const {
  return index_->sweep(k).timestamp_ns;
}

void RawlogSweeps::load(std::size_t k, core::LidarFrame& frame,
                        std::optional<Eigen::Isometry3d>& pose) {
  mrptio::Frame f;
  index_->read(k, f);
  frame = std::move(f.frame);
  pose.reset();
  if (f.odometry) pose = *f.odometry * f.mount;
}

std::string RawlogSweeps::describe() const {
  return "rawlog '" + index_->path() + "'";
}

const std::string& RawlogSweeps::sensorLabel() const {
  return index_->sensorLabel();
}

}  // namespace dynobj::label
