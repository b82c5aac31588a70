// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogFrameSource.h"

#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose3D.h>

#include "dynobj/mrptio/PoseConversion.h"
#include "dynobj/mrptio/TimeConversion.h"

namespace dynobj::mrptio {

RawlogFrameSource::RawlogFrameSource(std::string rawlog, ObservationConverter converter,
                                     Options opts)
    : path_(std::move(rawlog)), converter_(std::move(converter)), opts_(std::move(opts)) {
  rewind();
}

void RawlogFrameSource::rewind() {
  reader_ = std::make_unique<RawlogReader>(path_);
  pending_.clear();
  pending_pos_ = 0;
  frames_ = 0;
  odometry_.reset();
  skip_before_ns_ = std::numeric_limits<std::int64_t>::min();
}

std::string RawlogFrameSource::noFramesDetail() const {
  std::string seen;
  for (const auto& [label, cls] : labels_) seen += " '" + label + "' (" + cls + ")";
  return (opts_.sensor_label.empty() ? "" : " with sensor label '" + opts_.sensor_label + "'") +
         std::string("; labels seen:") + (seen.empty() ? " none" : seen);
}

mrpt::obs::CObservation::Ptr RawlogFrameSource::nextObservation() {
  for (;;) {
    while (pending_pos_ < pending_.size()) {
      const auto obs = pending_[pending_pos_++];
      if (!obs) continue;
      labels_.emplace(obs->sensorLabel, obs->GetRuntimeClass()->className);
      if (const auto* odo = dynamic_cast<const mrpt::obs::CObservationOdometry*>(obs.get())) {
        odometry_ = toIsometry(mrpt::poses::CPose3D(odo->odometry));
        continue;
      }
      if (!ObservationConverter::isLidarObservation(*obs)) continue;
      if (!opts_.sensor_label.empty() && obs->sensorLabel != opts_.sensor_label) continue;
      if (toUnixNs(obs->timestamp) < skip_before_ns_) {
        frames_++;
        continue;
      }
      return obs;
    }
    if (!reader_->next(entry_)) return nullptr;
    if (entry_.index > opts_.to) return nullptr;
    pending_.clear();
    pending_pos_ = 0;
    if (entry_.index >= opts_.from) pending_ = entry_.observations();
  }
}

bool RawlogFrameSource::nextTime(std::int64_t& timestamp_ns) {
  const auto obs = nextObservation();
  if (!obs) return false;
  frames_++;
  timestamp_ns = toUnixNs(obs->timestamp);
  return true;
}

bool RawlogFrameSource::next(Frame& f) {
  const auto obs = nextObservation();
  if (!obs) return false;
  f.stats = converter_.convert(*obs, f.frame);
  mrpt::poses::CPose3D mount;
  obs->getSensorPose(mount);
  f.index = frames_++;
  f.entry = entry_.index;
  f.where = "'" + path_ + "' entry " + std::to_string(entry_.index);
  f.sensor_label = obs->sensorLabel;
  f.mount = toIsometry(mount);
  f.odometry = odometry_;
  f.viewpoint.reset();
  f.observation = obs;
  return true;
}

}  // namespace dynobj::mrptio
