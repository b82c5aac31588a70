// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrpt/LidarObservationStream.h"

namespace dynobj::mrpt {

LidarObservationStream::LidarObservationStream(const std::string& rawlog,
                                               ObservationConverter converter, Options opts)
    : reader_(rawlog), converter_(std::move(converter)), opts_(std::move(opts)) {}

bool LidarObservationStream::next(Item& item) {
  for (;;) {
    while (pending_pos_ < pending_.size()) {
      const auto obs = pending_[pending_pos_++];
      if (!obs) continue;
      labels_.emplace(obs->sensorLabel, obs->GetRuntimeClass()->className);
      if (!ObservationConverter::isLidarObservation(*obs)) continue;
      if (!opts_.sensor_label.empty() && obs->sensorLabel != opts_.sensor_label) continue;
      item.entry = entry_.index;
      item.observation = obs;
      item.stats = converter_.convert(*obs, item.frame);
      return true;
    }
    if (!reader_.next(entry_)) return false;
    if (entry_.index > opts_.to) return false;
    pending_.clear();
    pending_pos_ = 0;
    if (entry_.index >= opts_.from) pending_ = entry_.observations();
  }
}

}  // namespace dynobj::mrpt
