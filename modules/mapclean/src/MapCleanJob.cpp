// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapCleanJob.h"

#include <dynobj/core/Config.h>
#include <dynobj/core/FrameImages.h>
#include <dynobj/io/Png.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/SequenceRunner.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <iomanip>
#include <memory>
#include <stdexcept>

#include "dynobj/mapclean/ChunkMerge.h"
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
  if (o.chunk)
    for (const char* name : {"overlap.tum", "chunk.ini"}) files.push_back(o.out_dir + "/" + name);
  if (!o.export_kth.empty()) files.push_back(o.export_kth);
  return files;
}

std::string ChunkRange::describe() const {
  const auto s = [](double t) {
    char b[40];
    std::snprintf(b, sizeof(b), "%.9g s", t);
    return std::string(b);
  };
  return s(from) + " to " + (std::isfinite(to) ? s(to) : std::string("the end"));
}

void ChunkRange::validate() const {
  if (!(from >= 0) || !std::isfinite(from))
    throw std::invalid_argument("--chunk-from must be a time >= 0 [s] since the first scan");
  if (!(to > from))
    throw std::invalid_argument("--chunk-to must be later than --chunk-from: " + describe());
  if (!(overlap > 0) || !std::isfinite(overlap))
    throw std::invalid_argument(
        "--chunk-overlap must be > 0 s: the chunks are aligned by the scans they share");
}

std::vector<std::string> writeMaps(const std::string& out_dir, const MapFormats& f,
                                   const std::vector<MapPoint>& st, const std::vector<MapPoint>& dy,
                                   double png_resolution) {
  std::vector<std::string> files;
  for (const auto& [name, pts] : {std::pair{"static", &st}, std::pair{"dynamic", &dy}}) {
    const std::string base = out_dir + "/" + name;
    if (f.ply) writePly(files.emplace_back(base + ".ply"), *pts);
    if (f.pointsmap) writePointsMapFile(files.emplace_back(base + ".pointsmap"), *pts);
    if (f.txt) writePointsMapText(files.emplace_back(base + ".txt"), *pts);
  }
  if (f.png) {
    const TopDownView view = TopDownView::fit(st, dy, png_resolution);
    const std::vector<LegendEntry> legend = {
        {cv::Scalar(200, 200, 200), "static (brighter = higher)"},
        {cv::Scalar(0, 0, 255), "dynamic (removed)"}};
    cv::Mat map = renderTopDown(view, st, dy), clean = renderTopDown(view, st, {});
    drawLegendAndScale(map, view, legend);
    drawLegendAndScale(clean, view, {legend[0]});
    io::writePngAtomically(files.emplace_back(out_dir + "/map.png"), map);
    io::writePngAtomically(files.emplace_back(out_dir + "/static.png"), clean);
  }
  return files;
}

MapScores scoreMap(const std::vector<MapPoint>& st, double tolerance, ScanSource* scans,
                   const mrptio::GroundTruth* labels, const std::string& gt_pcd,
                   const std::vector<io::TimedPose>& poses, double min_range,
                   const MapCleanProgress& progress) {
  MapEvaluator eval(st, tolerance);
  if (!labels) {
    for (const MapPoint& p : readPcd(gt_pcd).points) eval.add(p.x, p.y, p.z, p.intensity != 0.f);
    return eval.scores();
  }
  Scan scan;
  std::size_t k = 0;  // the poses are in the scans' order
  while (k < poses.size() && scans->next(scan)) {
    if (scan.frame.timestamp_ns != poses[k].timestamp_ns) continue;  // not mapped (an overlap)
    const cv::Mat_<std::uint8_t> gt = labels->mask(scan.frame, scan.index);
    forEachWorldPoint(scan.frame, poses[k].pose, min_range, [&](int r, int c, const MapPoint& p) {
      eval.add(p.x, p.y, p.z, gt(r, c) != 0);
    });
    ++k;
    if (progress)
      progress("evaluate", k, poses.size(),
               static_cast<double>(k) / static_cast<double>(poses.size()));
  }
  return eval.scores();
}

MapCleanSummary runMapClean(const MapCleanOptions& o, const MapCleanProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
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
  // A chunk: only its scans are mapped; those of the overlap before and after are read too.
  constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();
  std::int64_t first_scan = 0, own_begin = std::numeric_limits<std::int64_t>::min(),
               own_end = kNever;
  auto source = openScanSource(o.input, o.scan_options);
  const auto window = [&](std::unique_ptr<ScanSource> scans) -> std::unique_ptr<ScanSource> {
    if (!o.chunk) return scans;
    const auto overlap = static_cast<std::int64_t>(std::llround(o.chunk->overlap * 1e9));
    return std::make_unique<TimeWindowSource>(std::move(scans), own_begin - overlap,
                                              own_end == kNever ? own_end : own_end + overlap);
  };
  if (o.chunk) {
    o.chunk->validate();
    first_scan = firstScanTime(*source);
    own_begin = first_scan + static_cast<std::int64_t>(std::llround(o.chunk->from * 1e9));
    if (std::isfinite(o.chunk->to))
      own_end = first_scan + static_cast<std::int64_t>(std::llround(o.chunk->to * 1e9));
    source = window(std::move(source));
  }
  PoseSourceOptions pose_options = o.pose_options;
  pose_options.ego_available = !labels;
  auto poses = makePoseSource(o.poses, pose_options);
  mrptio::SequenceOptions pass1;  // detection, ground truth checked against every scan
  pass1.detector = o.detector;
  pass1.detect = !labels;
  pass1.single_sensor = true;       // one LiDAR per map
  pass1.require_frames = !o.chunk;  // a chunk's range without a scan: said below
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
  std::vector<io::TimedPose> mapped_poses;     // for the metrics' pass (a few MB per hour)
  std::unique_ptr<io::TumWriter> overlap_tum;  // a chunk's scans read but not mapped
  if (o.chunk)
    overlap_tum = std::make_unique<io::TumWriter>(
        out + "overlap.tum", "sensor pose of the scans a dynobj-mapclean chunk read, not mapped");
  std::int64_t last_mapped = 0;
  std::size_t scans_read = 0;
  const auto own = [&](std::int64_t t) { return t >= own_begin && t < own_end; };

  const auto mapScan = [&](const Scan& s, const FrameRecord& rec) {
    if (!own(rec.timestamp_ns)) {  // a chunk's overlap: its views count, its points are not mapped
      cleaner.look(s.frame, rec.sensor_pose);
      overlap_tum->write(rec.timestamp_ns, rec.sensor_pose);
      (rec.timestamp_ns < own_begin ? sum.scans_before : sum.scans_after)++;
      return;
    }
    last_mapped = rec.timestamp_ns;
    const cv::Mat_<std::uint8_t> mask = cleaner.dynamicMask(s.frame, rec);
    cleaner.map(s.frame, mask, rec.sensor_pose);
    if (simplemap) simplemap->add(s, mask, rec.sensor_pose);
    if (exporter) {
      const cv::Mat_<std::uint8_t> gt =
          gt_labels ? gt_labels->mask(s.frame, s.index) : cv::Mat_<std::uint8_t>();
      exporter->add(s.frame, rec.sensor_pose, gt_labels ? &gt : nullptr);
    }
    tum.write(rec.timestamp_ns, rec.sensor_pose);
    if (!o.ground_truth.empty()) mapped_poses.push_back({rec.timestamp_ns, rec.sensor_pose});
    ++sum.scans;
    if (!progress) return;
    // The share mapped: of the input's bytes, as many as read so far times the scans mapped of
    // those read (the mapping trails the reading); a chunk with an end: of its time span.
    const double read = source->progress();  // negative: not known
    double done = read < 0 ? -1.0
                           : read * static_cast<double>(sum.scans + sum.scans_before) /
                                 static_cast<double>(std::max<std::size_t>(1, scans_read));
    if (o.chunk && own_end != kNever) {
      const double read_begin = static_cast<double>(own_begin) - 1e9 * o.chunk->overlap;
      const double read_end = static_cast<double>(own_end) + 1e9 * o.chunk->overlap;
      done = (static_cast<double>(rec.timestamp_ns) - read_begin) / (read_end - read_begin);
    }
    progress("map", sum.scans, 0, done < 0 ? done : std::min(done, 1.0));
  };

  // One pass over the input. With back-fill, a scan is mapped backfill_window seconds after its
  // detection, read again by a second reader that trails the detector's: memory holds the
  // window's records (no points), never the recording.
  const bool backfill = !labels && o.clean.backfill_window > 0;
  const auto window_ns = static_cast<std::int64_t>(o.clean.backfill_window * 1e9);
  std::unique_ptr<ScanSource> trailing;
  if (backfill) trailing = window(openScanSource(o.input, o.scan_options));
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
    scans_read++;
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
  const bool reached_end = o.chunk && dynamic_cast<const TimeWindowSource&>(*source).reachedEnd();
  if (o.chunk && sum.scans == 0)
    throw std::runtime_error("no scan of " + source->describe() + " from " + o.chunk->describe() +
                             " after its first scan");

  sum.voted = cleaner.finish();
  sum.seen_through = cleaner.moveSeenThrough();
  const std::vector<MapPoint> st = cleaner.staticMap().points(), dy = cleaner.dynamicMap().points();
  sum.points_static = cleaner.staticMap().pointsInserted();
  sum.points_dynamic = cleaner.dynamicMap().pointsInserted();
  sum.map_static = st.size();
  sum.map_dynamic = dy.size();
  sum.backfilled = cleaner.backfilledPixels();
  sum.confirmed_tracks = cleaner.confirmedTracks().size();
  sum.files = writeMaps(o.out_dir, o.formats, st, dy, o.png_resolution);
  tum.close();
  sum.files.push_back(out + "poses.tum");
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
    source->rewind();
    sum.scores = scoreMap(st, o.tolerance, source.get(), gt_labels, o.ground_truth, mapped_poses,
                          o.clean.min_range, progress);
  }
  if (o.chunk) {
    overlap_tum->close();
    sum.files.push_back(out + "overlap.tum");
    ChunkInfo info;
    info.input = o.input;
    info.first_scan_ns = first_scan;
    info.range = *o.chunk;
    info.scans = sum.scans;
    info.scans_before = sum.scans_before;
    info.scans_after = sum.scans_after;
    info.reached_end = reached_end;
    info.last_scan = 1e-9 * static_cast<double>(last_mapped - first_scan);
    info.voxel_size = o.clean.voxel_size;
    info.dynamic_vote = o.clean.dynamic_vote;
    info.min_range = o.clean.min_range;
    info.poses = sum.poses;
    info.formats = o.formats.toString();
    info.write(sum.files.emplace_back(out + "chunk.ini"));
  }
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sum;
}

}  // namespace dynobj::mapclean
