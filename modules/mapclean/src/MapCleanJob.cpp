// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapCleanJob.h"

#include <dynobj/core/Config.h>
#include <dynobj/core/FrameImages.h>
#include <dynobj/io/Png.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/SequenceRunner.h>

#include <chrono>
#include <deque>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <stdexcept>

#include "dynobj/mapclean/GroundLeveler.h"
#include "dynobj/mapclean/KthExport.h"
#include "dynobj/mapclean/MrptOutputs.h"
#include "dynobj/mapclean/PointCloudIO.h"
#include "dynobj/mapclean/TopDownImage.h"

namespace dynobj::mapclean {
namespace {

namespace fs = std::filesystem;

bool isPcd(const std::string& f) {
  return fs::path(f).extension() == ".pcd";
}

/// The formats by name, in the order of MapFormats::toString().
std::vector<std::pair<std::string, bool MapFormats::*>> formatNames() {
  return {{"ply", &MapFormats::ply},
          {"pointsmap", &MapFormats::pointsmap},
          {"txt", &MapFormats::txt},
          {"png", &MapFormats::png},
          {"simplemap", &MapFormats::simplemap}};
}

}  // namespace

MapFormats MapFormats::parse(const std::string& list) {
  MapFormats f;
  for (const auto& [name, member] : formatNames()) f.*member = false;
  if (list == "all") {
    for (const auto& [name, member] : formatNames()) f.*member = true;
    return f;
  }
  std::vector<std::string> names;
  for (const auto& [name, member] : formatNames()) names.push_back(name);
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    const std::string item = list.substr(begin, end - begin);
    begin = end + 1;
    bool known = false;
    for (const auto& [name, member] : formatNames())
      if (item == name) f.*member = known = true;
    if (known) continue;
    if (item.empty())
      throw std::invalid_argument("--formats '" + list +
                                  "': an empty name (a comma-separated list of ply, pointsmap, "
                                  "txt, png, simplemap, or all)");
    const std::string near = core::closestName(item, names);
    throw std::invalid_argument(
        "--formats: unknown format '" + item + "'" +
        (near.empty() ? "" : " (did you mean '" + near + "'?)") +
        "; one or more of ply, pointsmap, txt, png, simplemap (comma-separated), or all");
  }
  return f;
}

std::string MapFormats::toString() const {
  std::string s;
  for (const auto& [name, member] : formatNames())
    if (this->*member) s += (s.empty() ? "" : ",") + name;
  return s;
}

std::vector<std::string> outputFiles(const MapCleanOptions& o) {
  std::vector<std::string> files;
  const MapFormats& f = o.formats;
  for (const char* name : {"static", "dynamic"}) {
    const std::string base = o.out_dir + "/" + name;
    if (f.ply) files.push_back(base + ".ply");
    if (f.pointsmap) files.push_back(base + ".pointsmap");
    if (f.txt) files.push_back(base + ".txt");
  }
  if (f.png)
    for (const char* png : {"map.png", "static.png"}) files.push_back(o.out_dir + "/" + png);
  files.push_back(o.out_dir + "/poses.tum");
  if (f.simplemap) files.push_back(o.out_dir + "/cleaned.simplemap");
  if (!o.export_kth.empty()) files.push_back(o.export_kth);
  return files;
}

MapCleanSummary runMapClean(const MapCleanOptions& o, const MapCleanProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto report = [&](const char* stage, std::size_t done, std::size_t total) {
    if (progress) progress(stage, done, total);
  };
  if (!o.overwrite)
    for (const std::string& f : outputFiles(o))
      if (fs::exists(f))
        throw std::runtime_error("output '" + f + "' exists (use -w to replace it)");
  std::optional<mrptio::GroundTruth> labels;  // the classification instead of the detector's
  if (!o.labels.empty()) {
    if (o.poses == "ego")
      throw std::runtime_error(
          "--poses ego needs the detector's ego-motion, which does not run with --labels: choose "
          "another pose source");
    if (!fs::is_regular_file(o.labels))
      throw std::runtime_error("label file '" + o.labels + "' does not exist");
    labels.emplace(o.labels, mrptio::GroundTruth::Options{"label file", false});
  }
  auto source = openScanSource(o.input, o.scan_options);
  PoseSourceOptions pose_options = o.pose_options;
  pose_options.ego_available = !labels;
  auto poses = makePoseSource(o.poses, pose_options);
  mrptio::SequenceOptions pass1;  // detection, ground truth checked against every scan
  pass1.detector = o.detector;
  pass1.detect = !labels;
  pass1.single_sensor = true;  // one LiDAR per map
  if (!o.ground_truth.empty()) {
    if (!fs::is_regular_file(o.ground_truth))
      throw std::runtime_error("ground truth '" + o.ground_truth + "' does not exist");
    if (!isPcd(o.ground_truth)) pass1.ground_truth = o.ground_truth;
  }
  mrptio::SequenceRunner runner(*source, pass1);
  const mrptio::GroundTruth* gt_labels = runner.groundTruth() ? &*runner.groundTruth() : nullptr;
  if (o.out_dir.empty()) throw std::runtime_error("no output folder");
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (!fs::is_directory(o.out_dir))
    throw std::runtime_error("cannot create output directory '" + o.out_dir + "'");
  const std::string out = o.out_dir + "/";

  MapCleanSummary sum;
  MapCleaner cleaner(o.clean);
  std::unique_ptr<CleanedSimplemapWriter> simplemap;
  if (o.formats.simplemap)
    simplemap = std::make_unique<CleanedSimplemapWriter>(out + "cleaned.simplemap",
                                                         o.keyframe_distance, o.keyframe_angle);
  std::unique_ptr<KthExporter> exporter;
  if (!o.export_kth.empty())
    exporter = std::make_unique<KthExporter>(o.export_kth, gt_labels != nullptr, o.overwrite);
  io::TumWriter tum(out + "poses.tum", "sensor pose in the world, as mapped by dynobj-mapclean");
  std::vector<Eigen::Isometry3d> mapped_poses;  // for the metrics' pass (a few MB per hour)

  const auto mapScan = [&](const Scan& s, const FrameRecord& rec) {
    const cv::Mat_<std::uint8_t> mask = cleaner.dynamicMask(s.frame, rec);
    cleaner.map(s.frame, mask, rec.sensor_pose);
    if (simplemap) simplemap->add(s, mask, rec.sensor_pose);
    if (exporter) {
      const cv::Mat_<std::uint8_t> gt =
          gt_labels ? gt_labels->mask(s.frame, s.index) : cv::Mat_<std::uint8_t>();
      exporter->add(s.frame, rec.sensor_pose, gt_labels ? &gt : nullptr);
    }
    tum.write(rec.timestamp_ns, rec.sensor_pose);
    if (!o.ground_truth.empty()) mapped_poses.push_back(rec.sensor_pose);
    report("map", ++sum.scans, 0);
  };

  // One pass over the input. With back-fill, a scan is mapped backfill_window seconds after its
  // detection, read again by a second reader that trails the detector's: memory holds the
  // window's records (no points), never the recording.
  const bool backfill = !labels && o.clean.backfill_window > 0;
  const auto window_ns = static_cast<std::int64_t>(o.clean.backfill_window * 1e9);
  std::unique_ptr<ScanSource> trailing;
  if (backfill) trailing = openScanSource(o.input, o.scan_options);
  std::deque<FrameRecord> waiting;
  Scan scan;
  const auto mapOldest = [&] {
    if (!trailing->next(scan) || scan.frame.timestamp_ns != waiting.front().timestamp_ns)
      throw std::runtime_error(source->describe() + " changed while it was read");
    mapScan(scan, waiting.front());
    waiting.pop_front();
  };
  GroundLeveler leveler;
  runner.run([&](const mrptio::FrameResult& fr) {
    const Scan& s = fr.frame;
    Eigen::Isometry3d pose =
        poses->pose(s, fr.detection ? fr.detection->ego_motion : core::EgoMotion{});
    if (o.clean.level_poses)
      if (const auto ground = leveler.fit(s.frame)) pose = leveler.level(pose, *ground);
    FrameRecord rec;
    if (labels) {
      std::size_t k = 0;
      const io::LabelSweep& sweep = labels->sweep(s.frame, s.index, &k);
      if (!labels->labels().isReviewed(k)) sum.unreviewed_sweeps++;
      rec = FrameRecord{s.frame.timestamp_ns, pose, sweep.pixels, {}};
    } else {
      rec = cleaner.record(*fr.detection, pose);
      sum.data_faults.insert(sum.data_faults.end(), fr.detection->warnings.begin(),
                             fr.detection->warnings.end());
    }
    if (!backfill) return mapScan(s, rec);
    waiting.push_back(std::move(rec));
    while (waiting.size() > 1 && (waiting.back().timestamp_ns - waiting.front().timestamp_ns >
                                      window_ns ||  // or the clock went back: no waiting on it
                                  waiting.back().timestamp_ns < waiting.front().timestamp_ns))
      mapOldest();
  });
  while (!waiting.empty()) mapOldest();
  sum.poses = poses->describe();  // after the first scan: what "auto" chose

  sum.voted = cleaner.finish();
  sum.seen_through = cleaner.moveSeenThrough();
  const std::vector<MapPoint> st = cleaner.staticMap().points(), dy = cleaner.dynamicMap().points();
  sum.points_static = cleaner.staticMap().pointsInserted();
  sum.points_dynamic = cleaner.dynamicMap().pointsInserted();
  sum.map_static = st.size();
  sum.map_dynamic = dy.size();
  sum.backfilled = cleaner.backfilledPixels();
  sum.confirmed_tracks = cleaner.confirmedTracks().size();
  for (const auto& [name, pts] : {std::pair{"static", &st}, std::pair{"dynamic", &dy}}) {
    const std::string base = out + name;
    if (o.formats.ply) writePly(base + ".ply", *pts);
    if (o.formats.pointsmap) writePointsMapFile(base + ".pointsmap", *pts);
    if (o.formats.txt) writePointsMapText(base + ".txt", *pts);
  }
  if (o.formats.png) {
    const TopDownView view = TopDownView::fit(st, dy, o.png_resolution);
    const std::vector<LegendEntry> legend = {
        {cv::Scalar(200, 200, 200), "static (brighter = higher)"},
        {cv::Scalar(0, 0, 255), "dynamic (removed)"}};
    cv::Mat map = renderTopDown(view, st, dy), clean = renderTopDown(view, st, {});
    drawLegendAndScale(map, view, legend);
    drawLegendAndScale(clean, view, {legend[0]});
    io::writePngAtomically(out + "map.png", map);
    io::writePngAtomically(out + "static.png", clean);
  }
  tum.close();
  for (const std::string& f : outputFiles(o))
    if (f != o.export_kth && f != out + "cleaned.simplemap") sum.files.push_back(f);
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
      for (std::size_t k = 0; k < mapped_poses.size() && source->next(scan); k++) {
        const cv::Mat_<std::uint8_t> gt = gt_labels->mask(scan.frame, scan.index);
        forEachWorldPoint(
            scan.frame, mapped_poses[k], o.clean.min_range,
            [&](int r, int c, const MapPoint& p) { eval.add(p.x, p.y, p.z, gt(r, c) != 0); });
        report("evaluate", k + 1, mapped_poses.size());
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
