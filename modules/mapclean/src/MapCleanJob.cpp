// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapCleanJob.h"

#include <dynobj/core/AtomicFile.h>
#include <dynobj/core/FrameImages.h>
#include <dynobj/core/LabelFile.h>

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <stdexcept>

#include "dynobj/mapclean/GroundLeveler.h"
#include "dynobj/mapclean/KthExport.h"
#include "dynobj/mapclean/MapVisibilityCheck.h"
#include "dynobj/mapclean/MrptOutputs.h"
#include "dynobj/mapclean/PointCloudIO.h"
#include "dynobj/mapclean/TopDownImage.h"

namespace dynobj::mapclean {
namespace {

namespace fs = std::filesystem;

bool isPcd(const std::string& f) {
  return fs::path(f).extension() == ".pcd";
}

/// Ground-truth labels of one scan (label file v1), matched by timestamp.
class GroundTruthLabels {
 public:
  explicit GroundTruthLabels(const std::string& file)
      : file_(file), labels_(core::LabelFile::read(file)) {
    for (std::size_t i = 0; i < labels_.sweeps.size(); i++)
      by_time_[labels_.sweeps[i].timestamp_ns] = i;
  }
  /// Throws naming the file when the scan has no sweep or another size.
  cv::Mat_<std::uint8_t> mask(const Scan& s) const {
    const auto it = by_time_.find(s.frame.timestamp_ns);
    if (it == by_time_.end())
      throw std::runtime_error("ground truth '" + file_ + "' has no sweep at " +
                               std::to_string(s.frame.timestamp_ns) + " ns (scan " +
                               std::to_string(s.index) + "): the timestamps do not match");
    if (labels_.rows != s.frame.rows() || labels_.cols != s.frame.cols())
      throw std::runtime_error("ground truth '" + file_ + "' is " + std::to_string(labels_.rows) +
                               "x" + std::to_string(labels_.cols) + " but the scans are " +
                               std::to_string(s.frame.rows()) + "x" +
                               std::to_string(s.frame.cols()));
    cv::Mat_<std::uint8_t> m(s.frame.rows(), s.frame.cols(), std::uint8_t{0});
    for (auto px : labels_.sweeps[it->second].pixels)
      m(static_cast<int>(px) / m.cols, static_cast<int>(px) % m.cols) = 255;
    return m;
  }

 private:
  std::string file_;
  core::LabelFile labels_;
  std::map<std::int64_t, std::size_t> by_time_;
};

void writeTum(const std::string& path, const std::vector<FrameRecord>& recs) {
  core::AtomicFile f(path);
  auto& o = f.stream();
  o << "# timestamp tx ty tz qx qy qz qw  (sensor pose in the world, as mapped by "
       "dynobj-mapclean)\n";
  for (const FrameRecord& r : recs) {
    const Eigen::Quaterniond q(r.sensor_pose.linear());
    const Eigen::Vector3d& t = r.sensor_pose.translation();
    o << r.timestamp_ns / 1000000000 << "." << std::setw(9) << std::setfill('0')
      << r.timestamp_ns % 1000000000 << std::setfill(' ') << std::fixed << std::setprecision(6)
      << " " << t.x() << " " << t.y() << " " << t.z() << " " << q.x() << " " << q.y() << " "
      << q.z() << " " << q.w() << "\n";
  }
  f.commit();
}

void writePng(const std::string& path, const cv::Mat& img) {
  const std::string partial =
      core::partialName(path) + ".png";  // OpenCV picks the codec by extension
  core::writePng(partial, img);
  if (std::rename(partial.c_str(), path.c_str()) != 0)
    throw std::runtime_error("cannot rename '" + partial + "' to '" + path + "'");
}

}  // namespace

MapCleanSummary runMapClean(const MapCleanOptions& o, const MapCleanProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto report = [&](const char* stage, std::size_t done, std::size_t total) {
    if (progress) progress(stage, done, total);
  };
  auto source = openScanSource(o.input, o.scan_options);
  auto poses = makePoseSource(o.poses, o.pose_options);
  std::unique_ptr<GroundTruthLabels> gt_labels;
  if (!o.ground_truth.empty()) {
    if (!fs::is_regular_file(o.ground_truth))
      throw std::runtime_error("ground truth '" + o.ground_truth + "' does not exist");
    if (!isPcd(o.ground_truth)) gt_labels = std::make_unique<GroundTruthLabels>(o.ground_truth);
  }
  if (o.out_dir.empty()) throw std::runtime_error("no output folder");
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (!fs::is_directory(o.out_dir))
    throw std::runtime_error("cannot create output directory '" + o.out_dir + "'");
  const std::string out = o.out_dir + "/";

  MapCleanSummary sum;
  sum.poses = poses->describe();
  MapCleaner cleaner(o.clean);
  core::DynamicObjectDetector detector(o.detector);
  std::unique_ptr<CleanedSimplemapWriter> simplemap;
  if (o.write_simplemap)
    simplemap = std::make_unique<CleanedSimplemapWriter>(out + "cleaned.simplemap",
                                                         o.keyframe_distance, o.keyframe_angle);
  std::unique_ptr<KthExporter> exporter;
  if (!o.export_kth.empty())
    exporter = std::make_unique<KthExporter>(o.export_kth, gt_labels != nullptr);

  const bool two_pass = o.clean.second_pass;
  const auto mapScan = [&](const Scan& s, const FrameRecord& rec) {
    const cv::Mat_<std::uint8_t> mask = cleaner.dynamicMask(s.frame, rec, two_pass);
    cleaner.accumulate(s.frame, mask, rec.sensor_pose);
    if (simplemap) simplemap->add(s, mask, rec.sensor_pose);
    if (exporter) {
      const cv::Mat_<std::uint8_t> gt = gt_labels ? gt_labels->mask(s) : cv::Mat_<std::uint8_t>();
      exporter->add(s.frame, rec.sensor_pose, gt_labels ? &gt : nullptr);
    }
  };

  std::vector<FrameRecord> records;  // pixel lists dropped in single-pass mode
  GroundLeveler leveler;
  Scan scan;
  while (source->next(scan)) {
    const auto& r = detector.process(scan.frame);
    Eigen::Isometry3d pose = poses->pose(scan, r.ego_motion);
    if (o.clean.level_poses)
      if (const auto ground = leveler.fit(scan.frame)) pose = leveler.level(pose, *ground);
    records.push_back(cleaner.record(r, pose));
    if (gt_labels) gt_labels->mask(scan);  // a mismatch fails now, before any output exists
    if (!two_pass) {
      mapScan(scan, records.back());
      records.back().dynamic_pixels.clear();
      records.back().dynamic_pixels.shrink_to_fit();
    }
    report("detect", records.size(), 0);
  }
  if (records.empty()) throw std::runtime_error("no LiDAR scan in " + source->describe());
  sum.scans = records.size();
  if (two_pass) {
    source->rewind();
    for (std::size_t k = 0; k < records.size(); k++) {
      if (!source->next(scan) || scan.frame.timestamp_ns != records[k].timestamp_ns)
        throw std::runtime_error(source->describe() + " changed between passes");
      mapScan(scan, records[k]);
      report("map", k + 1, records.size());
    }
  }

  sum.voted = cleaner.finish();
  if (o.clean.free_space_check && o.clean.voxel_size > 0) {  // a further streaming pass
    MapVisibilityCheck check(o.clean.freeSpace(), cleaner.staticMap().voxels());
    source->rewind();
    const auto stride = static_cast<std::size_t>(o.clean.free_space_stride);
    for (std::size_t k = 0; k < records.size(); k++) {
      if (!source->next(scan) || scan.frame.timestamp_ns != records[k].timestamp_ns)
        throw std::runtime_error(source->describe() + " changed between passes");
      if (k % stride == 0) check.addScan(scan.frame, records[k].sensor_pose);
      report("free space", k + 1, records.size());
    }
    sum.seen_through = cleaner.moveToDynamic(check.seenThrough());
  }
  const std::vector<MapPoint> st = cleaner.staticMap().points(), dy = cleaner.dynamicMap().points();
  sum.points_static = cleaner.staticMap().pointsInserted();
  sum.points_dynamic = cleaner.dynamicMap().pointsInserted();
  sum.map_static = st.size();
  sum.map_dynamic = dy.size();
  sum.backfilled = cleaner.backfilledPixels();
  sum.confirmed_tracks = cleaner.confirmedTracks().size();
  for (const auto& [name, pts] : {std::pair{"static", &st}, std::pair{"dynamic", &dy}}) {
    writePly(out + name + ".ply", *pts);
    writePointsMapFiles(out + name, *pts);
    for (const char* ext : {".ply", ".pointsmap", ".txt"}) sum.files.push_back(out + name + ext);
  }
  const TopDownView view = TopDownView::fit(st, dy, o.png_resolution);
  writePng(out + "map.png", renderTopDown(view, st, dy));
  writePng(out + "static.png", renderTopDown(view, st, {}));
  writeTum(out + "poses.tum", records);
  for (const char* f : {"map.png", "static.png", "poses.tum"}) sum.files.push_back(out + f);
  if (simplemap) {
    simplemap->close();
    sum.keyframes = simplemap->keyframes();
    sum.files.push_back(out + "cleaned.simplemap");
  }
  if (exporter) {
    exporter->close();
    sum.exported_frames = exporter->frames();
    sum.exported_points = exporter->points();
    sum.files.push_back(o.export_kth);
  }

  if (!o.ground_truth.empty()) {  // metrics: the final static map against every GT point
    MapEvaluator eval(st, o.tolerance);
    if (gt_labels) {
      source->rewind();
      for (std::size_t k = 0; k < records.size() && source->next(scan); k++) {
        const cv::Mat_<std::uint8_t> gt = gt_labels->mask(scan);
        forEachWorldPoint(
            scan.frame, records[k].sensor_pose, o.clean.min_range,
            [&](int r, int c, const MapPoint& p) { eval.add(p.x, p.y, p.z, gt(r, c) != 0); });
        report("evaluate", k + 1, records.size());
      }
    } else {
      for (const MapPoint& p : readPcd(o.ground_truth).points)
        eval.add(p.x, p.y, p.z, p.intensity != 0.f);
    }
    sum.scores = eval.scores();
  }
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sum;
}

}  // namespace dynobj::mapclean
