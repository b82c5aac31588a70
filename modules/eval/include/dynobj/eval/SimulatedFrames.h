// SPDX-License-Identifier: BSD-3-Clause
// The simulator in process as a frame source for SequenceRunner (dynobj-bench: frames without
// files). Each sweep is simulated in next(); its ground truth stays in lastSweep().
#pragma once

#include <dynobj/mrptio/FrameSource.h>
#include <dynobj/sim/LidarSimulator.h>

#include <string>

namespace dynobj::eval {

class SimulatedFrames : public mrptio::FrameSource {
 public:
  /// `sim` must outlive this source.
  explicit SimulatedFrames(const sim::LidarSimulator& sim) : sim_(sim) {}
  bool next(mrptio::Frame& f) override {
    if (k_ >= sim_.scenario().frames) return false;
    sweep_ = sim_.simulate(k_);
    f.frame = sweep_.frame;
    f.index = f.entry = static_cast<std::size_t>(k_++);
    f.where = "sweep " + std::to_string(f.index);
    f.sensor_label = sim_.scenario().sensor_label;
    return true;
  }
  void rewind() override { k_ = 0; }
  std::string describe() const override { return "scenario '" + sim_.scenario().name + "'"; }
  const sim::SimulatedSweep& lastSweep() const { return sweep_; }

 private:
  const sim::LidarSimulator& sim_;
  sim::SimulatedSweep sweep_;
  int k_ = 0;
};

}  // namespace dynobj::eval
