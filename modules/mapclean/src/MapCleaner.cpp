// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapCleaner.h"

#include <dynobj/core/Config.h>
#include <dynobj/io/LabelFile.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace dynobj::mapclean {

void MapCleanParams::visit(core::ParamVisitor& v) {
  v.value("voxel_size", voxel_size, {0.0, 10.0});
  v.value("backfill_window", backfill_window, {0.0, 3600.0});
  v.value("box_margin", box_margin, {0.0, 5.0});
  v.value("min_range", min_range, {0.0, 1000.0});
  v.value("dynamic_vote", dynamic_vote, {0.0, 1000.0});
  v.value("level_poses", level_poses);
  v.value("free_space_check", free_space_check);
  v.value("free_space_stride", free_space_stride, {1, 1000000});
  v.value("final_after", final_after, {0.0, 86400.0});
  v.value("free_space_margin", visibility.margin, {0.0, 100.0});
  v.value("free_space_margin_rel", visibility.margin_rel, {0.0, 10.0});
  v.value("free_space_window", visibility.window, {0, 100});
  v.value("free_space_min_views", visibility.min_views, {1, 65535});
  v.value("free_space_ratio", visibility.ratio, {0.0, 1000.0});
  v.value("free_space_past", visibility.past, {0.0, 3600.0});
}

VisibilityParams MapCleanParams::freeSpace() const {
  VisibilityParams f = visibility;
  f.min_range = min_range;
  return f;
}

namespace {
const MapCleanParams& validated(const MapCleanParams& p) {
  p.validate();
  return p;
}
}  // namespace

MapCleaner::MapCleaner(const MapCleanParams& p, MapSink* sink)
    : p_(validated(p)),
      sink_(sink ? sink : &collected_),
      static_(p.voxel_size),
      dynamic_(p.voxel_size),
      visibility_(p.freeSpace()) {}

FrameRecord MapCleaner::record(const core::DetectionResult& r,
                               const Eigen::Isometry3d& sensor_pose) {
  FrameRecord rec;
  rec.timestamp_ns = r.timestamp_ns;
  rec.sensor_pose = sensor_pose;
  rec.dynamic_pixels = io::pixelsOfMask(r.dynamic);
  for (const core::TrackedObject& o : r.objects) {
    rec.objects.push_back({o.id, o.dynamic, o.box_min.cast<float>(), o.box_max.cast<float>()});
    if (o.dynamic) confirmed_.insert(o.id);
  }
  return rec;
}

cv::Mat_<std::uint8_t> MapCleaner::dynamicMask(const core::LidarFrame& frame,
                                               const FrameRecord& rec) const {
  cv::Mat_<std::uint8_t> mask(frame.rows(), frame.cols(), std::uint8_t{0});
  auto* m = mask.ptr<std::uint8_t>(0);
  for (auto px : rec.dynamic_pixels) {
    if (px >= frame.pixelCount()) throw std::out_of_range("dynamic pixel outside the frame");
    m[px] = 255;
  }
  if (p_.backfill_window <= 0) return mask;
  std::vector<ObjectBox> boxes;
  const float g = static_cast<float>(p_.box_margin);
  for (const ObjectBox& b : rec.objects)
    if (confirmed_.count(b.id)) {  // grown sideways and upwards; never below the object's base
      ObjectBox grown = b;
      grown.min -= Eigen::Vector3f(g, g, 0.f);
      grown.max += Eigen::Vector3f(g, g, g);
      boxes.push_back(grown);
    }
  if (boxes.empty()) return mask;
  for (int r = 0; r < frame.rows(); r++)
    for (int c = 0; c < frame.cols(); c++) {
      if (!frame.isValid(r, c) || mask(r, c)) continue;
      const cv::Vec3f& p = frame.xyz(r, c);
      for (const ObjectBox& b : boxes)
        if (p[0] >= b.min.x() && p[0] <= b.max.x() && p[1] >= b.min.y() && p[1] <= b.max.y() &&
            p[2] >= b.min.z() && p[2] <= b.max.z()) {
          mask(r, c) = 255;
          backfilled_++;
          break;
        }
    }
  return mask;
}

namespace {
/// The voxel vote: a static voxel with `vote` times fewer points than the dynamic one at its key.
bool outvoted(std::uint32_t n_static, std::uint32_t n_dynamic, double vote) {
  return vote > 0 && static_cast<double>(n_static) * vote <= static_cast<double>(n_dynamic);
}
}  // namespace

std::size_t voteVoxels(VoxelMap& stat, VoxelMap& dynamic, double vote) {
  if (vote <= 0 || stat.voxelSize() <= 0) return 0;
  return stat.moveVoxelsTo(dynamic,
                           [&](std::uint64_t key, std::uint32_t n_static, VoxelMap::Views) {
                             return !outvoted(n_static, dynamic.countAt(key), vote);
                           });
}

void MapCleaner::decide(std::uint32_t before) {
  using Slot = VoxelMap::Slot;
  const bool check = p_.free_space_check && p_.voxel_size > 0;
  for (const Slot& s : static_.extract([&](const Slot& v) {
         return v.cell.last < before && dynamic_.lastAt(v.key) < before;
       })) {
    const bool voted = outvoted(s.cell.n, dynamic_.countAt(s.key), p_.dynamic_vote);
    if (!voted && !(check && visibility_.isSeenThrough(s.cell.views))) {
      sink_->add(static_.centroid(s), false);
      continue;
    }
    dynamic_.merge(s);  // decided with the dynamic voxel at its key, just below
    (voted ? voted_ : seen_through_)++;
  }
  for (const Slot& s : dynamic_.extract(
           [&](const Slot& v) { return v.cell.last < before && !static_.contains(v.key); }))
    sink_->add(dynamic_.centroid(s), true);
}

void MapCleaner::finish() {
  if (p_.voxel_size <= 0) {  // every point kept: nothing to decide
    for (const MapPoint& p : static_.points()) sink_->add(p, false);
    for (const MapPoint& p : dynamic_.points()) sink_->add(p, true);
    return;
  }
  decide(std::numeric_limits<std::uint32_t>::max());
}

std::uint32_t MapCleaner::stampOf(std::int64_t timestamp_ns) {
  if (!stamped_) first_ns_ = timestamp_ns;
  stamped_ = true;
  const std::int64_t ms = (timestamp_ns - first_ns_) / 1000000;
  return static_cast<std::uint32_t>(std::clamp<std::int64_t>(ms, 0, 0xfffffffe));
}

void MapCleaner::map(const core::LidarFrame& frame, const cv::Mat_<std::uint8_t>& dynamic_mask,
                     const Eigen::Isometry3d& sensor_pose) {
  const bool check = p_.free_space_check && p_.voxel_size > 0;
  const std::uint32_t now = stampOf(frame.timestamp_ns);
  std::vector<std::uint64_t> opened;  // static voxels new in the map: the past scans' views
  forEachWorldPoint(frame, sensor_pose, p_.min_range, [&](int r, int c, const MapPoint& p) {
    if (dynamic_mask(r, c))
      dynamic_.insert(p, now);
    else if (static_.insert(p, now) && check)
      opened.push_back(static_.keyOf(p.x, p.y, p.z));
  });
  if (check) visibility_.countPast(static_, opened, frame.timestamp_ns);
  look(frame, sensor_pose);
  peak_voxels_ = std::max(peak_voxels_, static_.size() + dynamic_.size());
  const auto after = static_cast<std::uint32_t>(std::llround(p_.final_after * 1000.0));
  if (after == 0 || p_.voxel_size <= 0 || now < after || now - decided_at_ < after / 4) return;
  decided_at_ = now;
  decide(now - after);
}

void MapCleaner::look(const core::LidarFrame& frame, const Eigen::Isometry3d& sensor_pose) {
  if (p_.free_space_check && p_.voxel_size > 0 &&
      mapped_ % static_cast<std::size_t>(p_.free_space_stride) == 0)
    visibility_.addScan(frame, sensor_pose, static_);
  mapped_++;
}

}  // namespace dynobj::mapclean
