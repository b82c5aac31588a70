// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/SequenceRunner.h"

#include <algorithm>
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
      held_(opts_.detector,
            [](const Held& h) -> const core::LidarFrame& { return h.frame.frame; }) {
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

bool SequenceRunner::step(const std::function<void(const FrameResult&)>& on_frame) {
  if (finished_) return false;
  // A frame held for the hindsight lag, now final: its callback.
  const auto release = [&](core::HindsightQueue<Held>::Item& h) {
    FrameResult r(h.data.frame);
    r.detection = &h.result;
    r.pose = h.data.pose;
    r.motion = h.data.motion;
    r.truth = h.data.truth;
    r.truth_index = h.data.truth_index;
    on_frame(r);
  };
  Frame& f = frame_;  // its buffers are reused from frame to frame
  if (frames_ >= opts_.max_frames || !source_.next(f)) {
    finished_ = true;
    held_.finish(release);  // the recording ends: each sensor's last frame revises once more
    return false;
  }
  frames_++;
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
  if (!opts_.detect || !held_.lagged()) {
    on_frame(r);
    return true;
  }
  const std::string label = f.sensor_label;
  held_.push(label, Held{std::move(f), r.pose, r.motion, r.truth, r.truth_index},
             r.detection->clone(), release);
  f = Frame{};
  return true;
}

std::size_t SequenceRunner::run(const std::function<void(const FrameResult&)>& on_frame) {
  while (step(on_frame)) {
  }
  if (frames_ == 0 && opts_.require_frames)
    throw std::runtime_error("no LiDAR observation in " + source_.describe() +
                             source_.noFramesDetail());
  return frames_;
}

}  // namespace dynobj::mrptio
