// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/SequenceRunner.h"

#include <algorithm>
#include <set>
#include <stdexcept>

namespace dynobj::mrptio {

cv::Mat_<std::uint8_t> FrameResult::truthMask() const {
  if (!truth) return {};
  return io::maskOfPixels(truth->pixels, frame.frame.rows(), frame.frame.cols());
}

SequenceRunner::SequenceRunner(FrameSource& source, SequenceOptions opts)
    : source_(source),
      opts_(std::move(opts)),
      bank_(opts_.detector),
      hindsight_(opts_.detector.hindsight, opts_.detector.region_growing,
                 opts_.detector.free_space) {
  if (!opts_.poses.empty()) poses_ = io::readPoseFile(opts_.poses, io::PoseFormat::Tum);
  if (!opts_.ground_truth.empty()) {
    truth_.emplace(opts_.ground_truth);
    opts_.single_sensor = true;
  }
}

const io::TimedPose* SequenceRunner::poseOf(const Frame& f) const {
  if (poses_.empty()) return nullptr;
  const std::int64_t t = f.frame.timestamp_ns;
  const io::TimedPose* p = io::findPose(poses_, t);
  if (!p)
    throw std::runtime_error("'" + opts_.poses + "' has no pose at " + std::to_string(t) +
                             " ns (frame " + std::to_string(f.index) + ")");
  return p;
}

std::size_t SequenceRunner::run(const std::function<void(const FrameResult&)>& on_frame) {
  Frame f;
  std::size_t n = 0;
  for (; n < opts_.max_frames && source_.next(f); n++) {
    if (opts_.single_sensor) {  // one LiDAR per output: a second label is an error
      if (first_label_.empty()) first_label_ = f.sensor_label;
      if (f.sensor_label != first_label_)
        throw std::runtime_error(source_.describe() + " holds several LiDARs ('" + first_label_ +
                                 "', '" + f.sensor_label + "'): choose one with --sensor-label");
    }
    FrameResult r(f);
    if (truth_) r.truth = &truth_->sweep(f.frame, f.index, &r.truth_index);
    r.pose = poseOf(f);
    if (r.pose) {
      const io::TimedPose*& prev = last_pose_[f.sensor_label];
      if (prev && opts_.poses_as_motion) {
        r.motion = prev->pose.inverse() * r.pose->pose;
        if (opts_.motion_model) r.motion = opts_.motion_model(*r.motion);
      }
      prev = r.pose;
    }
    if (opts_.detect) r.detection = &bank_.process(f.sensor_label, f.frame, r.motion);
    if (!opts_.detect || opts_.detector.hindsight.lag <= 0) {
      on_frame(r);
      continue;
    }
    hold(std::move(f), r);
    f = Frame{};
    release(on_frame, false);
  }
  std::set<std::string> sensors;  // the recording ends: each sensor's last frame revises once more
  for (const Held& h : held_) sensors.insert(h.frame.sensor_label);
  for (const std::string& label : sensors) revise(label, true);
  release(on_frame, true);
  if (n == 0 && opts_.require_frames)
    throw std::runtime_error("no LiDAR observation in " + source_.describe() +
                             source_.noFramesDetail());
  return n;
}

void SequenceRunner::hold(Frame&& f, const FrameResult& r) {
  Held& h = held_.emplace_back();
  h.detection = r.detection->clone();  // the detector reuses its images
  h.pose = r.pose;
  h.motion = r.motion;
  h.truth = r.truth;
  h.truth_index = r.truth_index;
  h.frame = std::move(f);
  revise(h.frame.sensor_label, false);
}

std::vector<core::Hindsight::Held> SequenceRunner::heldOf(const std::string& sensor_label) {
  std::vector<core::Hindsight::Held> same_sensor;
  for (Held& e : held_)
    if (e.frame.sensor_label == sensor_label) same_sensor.push_back({&e.frame.frame, &e.detection});
  return same_sensor;
}

void SequenceRunner::revise(const std::string& sensor_label, bool last) {
  hindsight_.revise(heldOf(sensor_label), last);
}

void SequenceRunner::settle(const std::string& sensor_label) {
  hindsight_.settle(heldOf(sensor_label));  // settle_distance, stop_check
}

void SequenceRunner::release(const std::function<void(const FrameResult&)>& on_frame, bool all) {
  while (!held_.empty()) {
    const Held& h = held_.front();
    if (!all) {
      const auto same = std::count_if(held_.begin(), held_.end(), [&](const Held& e) {
        return e.frame.sensor_label == h.frame.sensor_label;
      });
      if (same <= hindsight_.heldFrames(h.frame.frame.sensor.frequency)) return;
    }
    settle(h.frame.sensor_label);
    FrameResult r(h.frame);
    r.detection = &h.detection;
    r.pose = h.pose;
    r.motion = h.motion;
    r.truth = h.truth;
    r.truth_index = h.truth_index;
    on_frame(r);
    held_.pop_front();
  }
}

}  // namespace dynobj::mrptio
