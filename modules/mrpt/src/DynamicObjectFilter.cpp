// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrpt/DynamicObjectFilter.h"

#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include "detail.h"
#include "dynobj/mrpt/RangeScanTagging.h"

namespace dynobj::mrpt {

namespace mobs = ::mrpt::obs;

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

DynamicObjectFilter::DynamicObjectFilter(Options opts)
    : opts_(std::move(opts)), converter_(opts_.sensor) {
  opts_.detector.validate();
}

core::DynamicObjectDetector& DynamicObjectFilter::detectorFor(const std::string& label) {
  auto& d = detectors_[label];
  if (!d) d = std::make_unique<core::DynamicObjectDetector>(opts_.detector);
  return *d;
}

void DynamicObjectFilter::warn(const std::string& message) {
  summary_.warnings[message]++;
  summary_.passed_through++;
}

const core::DetectionResult* DynamicObjectFilter::filter(
    const mobs::CObservation::Ptr& obs, std::vector<mobs::CObservation::Ptr>* extra) {
  summary_.observations++;
  if (!obs || !ObservationConverter::isLidarObservation(*obs)) return nullptr;
  if (!opts_.sensor_label.empty() && obs->sensorLabel != opts_.sensor_label) return nullptr;
  const std::string cls = obs->GetRuntimeClass()->className;
  auto* scan3d = dynobj_rtti::isClass<mobs::CObservation3DRangeScan>(*obs)
                     ? dynamic_cast<mobs::CObservation3DRangeScan*>(obs.get())
                     : nullptr;

  if (scan3d && opts_.mode != FilterMode::Mark &&
      (scan3d->points3D_isExternallyStored() || scan3d->rangeImage_isExternallyStored())) {
    // Its points / ranges live in external files, which this filter must not rewrite (and MRPT
    // 2.5 keeps no pixel indices there): leave it untouched and say so.
    warn(std::string(toString(opts_.mode)) +
         ": externally stored CObservation3DRangeScan passed through (run rawlog-edit "
         "--de-externalize first)");
    return nullptr;
  }
  if (opts_.mode == FilterMode::Restore) {
    if (!scan3d) {
      warn("restore: " + cls + " keeps no dropped points; passed through");
      return nullptr;
    }
    scan3d->load();
    summary_.dynamic_points += restoreDynamic(*scan3d).points_restored;
    summary_.lidar++;
    return nullptr;
  }
  if (!scan3d && opts_.mode == FilterMode::Mark) {
    warn("mark: " + cls + " has no per-point label channel; passed through");
    return nullptr;
  }
  try {
    converter_.convert(*obs, frame_);
  } catch (const ConversionError& e) {
    warn(std::string("not processed: ") + e.what());
    return nullptr;
  }
  const core::DetectionResult& r = detectorFor(obs->sensorLabel).process(frame_);
  summary_.detector_ms += r.timings.total;
  const std::vector<std::uint8_t> point_mask = frame_.pointMaskFromPixelMask(r.dynamic);
  std::size_t n_dynamic = 0;
  for (auto m : point_mask) n_dynamic += m;

  // Points to hand back in split mode, in the sensor frame.
  auto removed = std::make_shared<::mrpt::maps::CSimplePointsMap>();
  if (scan3d) {
    if (opts_.mode == FilterMode::Split)
      for (std::size_t i = 0; i < point_mask.size(); i++)
        if (point_mask[i])
          removed->insertPoint(scan3d->points3D_x[i], scan3d->points3D_y[i], scan3d->points3D_z[i]);
    if (opts_.mode == FilterMode::Mark)
      markDynamic(*scan3d, r.dynamic);
    else
      dropDynamic(*scan3d, r.dynamic);
  } else if (auto* velo = dynamic_cast<mobs::CObservationVelodyneScan*>(obs.get())) {
    // Map insertion reads point_cloud when it is not empty: make it the kept points only.
    if (velo->point_cloud.size() == 0) velo->generatePointCloud();
    auto& pc = velo->point_cloud;
    if (pc.size() != point_mask.size()) {
      warn("drop: CObservationVelodyneScan point cloud changed size; passed through");
      return &r;
    }
    std::size_t w = 0;
    for (std::size_t i = 0; i < pc.size(); i++) {
      if (point_mask[i]) {
        if (opts_.mode == FilterMode::Split) removed->insertPoint(pc.x[i], pc.y[i], pc.z[i]);
        continue;
      }
      pc.x[w] = pc.x[i];
      pc.y[w] = pc.y[i];
      pc.z[w] = pc.z[i];
      pc.intensity[w] = pc.intensity[i];
      if (!pc.laser_id.empty()) pc.laser_id[w] = pc.laser_id[i];
      if (!pc.timestamp.empty()) pc.timestamp[w] = pc.timestamp[i];
      if (!pc.azimuth.empty()) pc.azimuth[w] = pc.azimuth[i];
      w++;
    }
    pc.x.resize(w), pc.y.resize(w), pc.z.resize(w), pc.intensity.resize(w);
    if (!pc.laser_id.empty()) pc.laser_id.resize(w);
    if (!pc.timestamp.empty()) pc.timestamp.resize(w);
    if (!pc.azimuth.empty()) pc.azimuth.resize(w);
    pc.pointsForLaserID.clear();
  } else if (auto* cloud = dynamic_cast<mobs::CObservationPointCloud*>(obs.get())) {
    std::vector<bool> del(point_mask.begin(), point_mask.end());
    if (opts_.mode == FilterMode::Split)
      for (std::size_t i = 0; i < del.size(); i++)
        if (del[i]) {
          float x, y, z;
          cloud->pointcloud->getPoint(i, x, y, z);
          removed->insertPoint(x, y, z);
        }
    cloud->pointcloud->applyDeletionMask(del);
  } else {
    warn(std::string(toString(opts_.mode)) + ": " + cls + " cannot drop points; passed through");
    return &r;
  }
  summary_.lidar++;
  summary_.points += point_mask.size();
  summary_.dynamic_points += n_dynamic;
  if (opts_.mode == FilterMode::Split && extra) {
    auto pc = std::make_shared<mobs::CObservationPointCloud>();
    pc->sensorLabel = obs->sensorLabel + "_DYNAMIC";
    pc->timestamp = obs->timestamp;
    ::mrpt::poses::CPose3D pose;
    obs->getSensorPose(pose);
    pc->sensorPose = pose;
    pc->pointcloud = removed;
    extra->push_back(pc);
  }
  return &r;
}

void DynamicObjectFilter::filter(mobs::CSensoryFrame& sf) {
  std::vector<mobs::CObservation::Ptr> extra;
  for (auto& o : sf) filter(o, &extra);
  for (auto& e : extra) sf.insert(e);
}

}  // namespace dynobj::mrpt
