// SPDX-License-Identifier: BSD-3-Clause
// The frames an offline run holds for the hindsight lag (docs/algorithm.md §9), one queue for
// every tool that writes with hindsight: SequenceRunner (dynobj-detect, dynobj-eval, mapclean)
// and the rawlog filter (rawlog-dynobj). Each frame just detected is held with a copy of its
// result and whatever the caller keeps with it (`T`); Hindsight revises the held frames of its
// sensor; a frame held for the lag (Hindsight::heldFrames of its sensor's frames) is settled
// (Hindsight::settle) and released to the caller, oldest first, in the order frames came in.
// Several sensors share the queue (the release order stays the arrival order); each is revised
// and settled on its own frames only. With lag = 0 every frame is released at once, unrevised.
// A frame after a time jump (core::FrameCheck) releases every held frame first (finish()).
#pragma once

#include <algorithm>
#include <deque>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "dynobj/core/DynamicObjectDetector.h"
#include "dynobj/core/Hindsight.h"

namespace dynobj::core {

template <class T>
class HindsightQueue {
 public:
  struct Item {
    std::string sensor;
    T data;
    DetectionResult result;  ///< revised by hindsight while held; final when released
  };
  /// Called for each released frame, oldest first.
  using Release = std::function<void(Item&)>;

  /// `frame_of`: the LidarFrame a held T carries (it must stay where it is while held).
  HindsightQueue(const DetectorParams& p, std::function<const LidarFrame&(const T&)> frame_of)
      : hindsight_(p.hindsight, p.region_growing, p.free_space), frame_of_(std::move(frame_of)) {}

  bool lagged() const { return hindsight_.params().lag > 0; }
  bool empty() const { return held_.empty(); }

  /// Holds a frame just detected (`result`: a copy that shares no pixel data with the detector,
  /// DetectionResult::clone), lets hindsight revise its sensor's held frames, and releases those
  /// held long enough.
  void push(std::string sensor, T data, DetectionResult result, const Release& release) {
    if (!lagged()) {
      Item now{std::move(sensor), std::move(data), std::move(result)};
      release(now);
      return;
    }
    // A time jump (FrameCheck): the tracks start anew with this frame, the held ones are final.
    if (std::any_of(result.warnings.begin(), result.warnings.end(),
                    [](const FrameWarning& w) { return w.fault == FrameFault::TimeJump; }))
      finish(release);
    held_.push_back(Item{std::move(sensor), std::move(data), std::move(result)});
    hindsight_.revise(heldOf(held_.back().sensor), false);
    releaseHeld(release, false);
  }

  /// The recording ended: each sensor's frames are revised once more, then all released.
  void finish(const Release& release) {
    std::set<std::string> sensors;
    for (const Item& h : held_) sensors.insert(h.sensor);
    for (const std::string& s : sensors) hindsight_.revise(heldOf(s), true);
    releaseHeld(release, true);
  }

 private:
  std::vector<Hindsight::Held> heldOf(const std::string& sensor) {
    std::vector<Hindsight::Held> out;
    for (Item& h : held_)
      if (h.sensor == sensor) out.push_back({&frame_of_(h.data), &h.result});
    return out;
  }

  void releaseHeld(const Release& release, bool all) {
    while (!held_.empty()) {
      Item& h = held_.front();
      if (!all) {
        const auto same = std::count_if(held_.begin(), held_.end(),
                                        [&](const Item& e) { return e.sensor == h.sensor; });
        if (same <= hindsight_.heldFrames(frame_of_(h.data).sensor.frequency)) return;
      }
      hindsight_.settle(heldOf(h.sensor));  // stop_check
      release(h);
      held_.pop_front();
    }
  }

  Hindsight hindsight_;
  std::function<const LidarFrame&(const T&)> frame_of_;
  std::deque<Item> held_;
};

}  // namespace dynobj::core
