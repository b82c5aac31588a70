// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/DynamicObjectFilter.h"

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservationPointCloud.h>

#include "ObservationClasses.h"

namespace dynobj::mrptio {

namespace mobs = mrpt::obs;

FilterMode parseFilterMode(const std::string& name) {
  if (name == "mark") return FilterMode::Mark;
  if (name == "drop") return FilterMode::Drop;
  if (name == "split") return FilterMode::Split;
  if (name == "restore") return FilterMode::Restore;
  throw std::invalid_argument("unknown mode '" + name + "' (mark, drop, split, restore)");
}

const char* toString(FilterMode m) {
  switch (m) {
    case FilterMode::Mark:
      return "mark";
    case FilterMode::Drop:
      return "drop";
    case FilterMode::Split:
      return "split";
    case FilterMode::Restore:
      return "restore";
  }
  return "?";
}

FilterSummary& FilterSummary::operator+=(const FilterSummary& o) {
  observations += o.observations;
  lidar += o.lidar;
  points += o.points;
  dynamic_points += o.dynamic_points;
  passed_through += o.passed_through;
  for (const auto& [msg, n] : o.warnings) warnings[msg] += n;
  detector_ms += o.detector_ms;
  for (const auto& [what, n] : o.seen) seen[what] += n;
  data_faults.insert(data_faults.end(), o.data_faults.begin(), o.data_faults.end());
  return *this;
}

std::map<core::FrameFault, std::size_t> FilterSummary::faultCounts() const {
  std::map<core::FrameFault, std::size_t> counts;
  for (const auto& [label, w] : data_faults) counts[w.fault]++;
  return counts;
}

void FilterSummary::see(const mobs::CObservation& obs) {
  seen["'" + obs.sensorLabel + "' (" + obs.GetRuntimeClass()->className + ")"]++;
}

std::string FilterSummary::nothingFiltered(const std::string& sensor_label) const {
  std::string found;
  for (const auto& [what, n] : seen)
    found += (found.empty() ? "" : ", ") + what + " x" + std::to_string(n);
  std::string why;
  for (const auto& [msg, n] : warnings)
    why += (why.empty() ? "" : "; ") + msg + " (" + std::to_string(n) + "x)";
  return "no LiDAR frame was filtered" +
         (sensor_label.empty() ? std::string() : " with sensor label '" + sensor_label + "'") +
         ": found " + (found.empty() ? "no observation" : found) +
         (why.empty() ? std::string()
                      : "; " + std::to_string(passed_through) + " LiDAR observations passed " +
                            "through: " + why) +
         " (check --sensor-label and --sensor; --allow-none when a run that filters nothing is "
         "expected)";
}

DynamicObjectFilter::DynamicObjectFilter(Options opts)
    : opts_(std::move(opts)), converter_(opts_.sensor), detectors_(opts_.detector) {}

void DynamicObjectFilter::warn(const std::string& message) {
  summary_.warnings[message]++;
  summary_.passed_through++;
}

bool DynamicObjectFilter::handles(const mobs::CObservation& obs) const {
  return detail::findObservationClass(obs) &&
         (opts_.sensor_label.empty() || obs.sensorLabel == opts_.sensor_label);
}

bool DynamicObjectFilter::converts(const mobs::CObservation& obs) const {
  if (!handles(obs)) return false;
  // filter()'s checks before its conversion, in the same order.
  const detail::ObservationClass* cls = detail::findObservationClass(obs);
  if (opts_.mode != FilterMode::Mark && cls->externallyStored && cls->externallyStored(obs))
    return false;
  if (opts_.mode == FilterMode::Restore) return false;
  return opts_.mode != FilterMode::Mark || cls->mark;
}

void DynamicObjectFilter::preconvert(const mobs::CObservation& obs, PreconvertedFrame& out) {
  try {
    converter_.convert(obs, out.frame);
    out.ok = true;
  } catch (const ConversionError& e) {
    out.ok = false;
    out.error = e.what();
  }
}

const core::DetectionResult* DynamicObjectFilter::filter(
    const mobs::CObservation::Ptr& obs, std::vector<mobs::CObservation::Ptr>* extra,
    PreconvertedFrame* pre) {
  const core::DetectionResult* r = detect(obs, pre);
  if (!r) return nullptr;
  tag(obs, pre ? pre->frame : frame_, *r, extra);
  return r;
}

const core::DetectionResult* DynamicObjectFilter::detect(const mobs::CObservation::Ptr& obs,
                                                         PreconvertedFrame* pre) {
  summary_.observations++;
  if (obs) summary_.see(*obs);
  if (!obs || !handles(*obs)) return nullptr;  // not a LiDAR observation (or not the chosen one)
  const detail::ObservationClass* cls = detail::findObservationClass(*obs);
  const std::string mode = toString(opts_.mode);
  if (opts_.mode != FilterMode::Mark && cls->externallyStored && cls->externallyStored(*obs)) {
    // Its points / ranges live in external files, which this filter must not rewrite (and MRPT
    // 2.5 keeps no pixel indices there): leave it untouched and say so.
    warn(mode + ": externally stored " + cls->name +
         " passed through (run rawlog-edit --de-externalize first)");
    return nullptr;
  }
  if (opts_.mode == FilterMode::Restore) {
    if (!cls->restore) {
      warn("restore: " + std::string(cls->name) + " keeps no dropped points; passed through");
      return nullptr;
    }
    summary_.dynamic_points += cls->restore(*obs).points_restored;
    summary_.lidar++;
    return nullptr;
  }
  if (opts_.mode == FilterMode::Mark && !cls->mark) {
    warn("mark: " + std::string(cls->name) + " has no per-point label channel; passed through");
    return nullptr;
  }
  // The per-frame step shared with SequenceRunner: convert -> the sensor's detector.
  if (pre && !pre->ok) {  // converted ahead, in the same order
    warn("not processed: " + pre->error);
    return nullptr;
  }
  if (!pre) {
    try {
      converter_.convert(*obs, frame_);
    } catch (const ConversionError& e) {
      warn(std::string("not processed: ") + e.what());
      return nullptr;
    }
  }
  const core::DetectionResult& r = detectors_.process(obs->sensorLabel, pre ? pre->frame : frame_);
  summary_.detector_ms += r.timings.total;
  return &r;
}

void DynamicObjectFilter::tag(const mobs::CObservation::Ptr& obs, const core::LidarFrame& frame,
                              const core::DetectionResult& r,
                              std::vector<mobs::CObservation::Ptr>* extra) {
  const detail::ObservationClass* cls = detail::findObservationClass(*obs);
  const std::string mode = toString(opts_.mode);
  const std::vector<std::uint8_t> point_mask = frame.pointMaskFromPixelMask(r.dynamic);
  std::size_t n_dynamic = 0;
  for (auto m : point_mask) n_dynamic += m;

  auto removed = std::make_shared<mrpt::maps::CSimplePointsMap>();  // split: sensor frame
  const bool split = opts_.mode == FilterMode::Split;
  if (opts_.mode == FilterMode::Mark) {
    cls->mark(*obs, r.dynamic);
  } else if (!cls->drop) {
    warn(mode + ": " + cls->name + " cannot drop points; passed through");
    return;
  } else {
    try {
      cls->drop(*obs, r.dynamic, point_mask, split ? removed.get() : nullptr);
    } catch (const ConversionError& e) {
      warn(mode + ": " + e.what() + "; passed through");
      return;
    }
  }
  summary_.lidar++;
  for (const core::FrameWarning& w : r.warnings)
    summary_.data_faults.emplace_back(obs->sensorLabel, w);
  summary_.points += point_mask.size();
  summary_.dynamic_points += n_dynamic;
  if (split && extra) {
    auto pc = std::make_shared<mobs::CObservationPointCloud>();
    pc->sensorLabel = obs->sensorLabel + "_DYNAMIC";
    pc->timestamp = obs->timestamp;
    mrpt::poses::CPose3D pose;
    obs->getSensorPose(pose);
    pc->sensorPose = pose;
    pc->pointcloud = removed;
    extra->push_back(pc);
  }
}

void DynamicObjectFilter::filter(mobs::CSensoryFrame& sf) {
  std::vector<mobs::CObservation::Ptr> extra;
  for (auto& o : sf) filter(o, &extra);
  for (auto& e : extra) sf.insert(e);
}

}  // namespace dynobj::mrptio
