// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MapCleanJob.h"

#include <dynobj/core/Config.h>
#include <dynobj/io/FrameImages.h>
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

namespace {

constexpr std::int64_t kNever = std::numeric_limits<std::int64_t>::max();

std::int64_t nanoseconds(double s) {
  return static_cast<std::int64_t>(std::llround(s * 1e9));
}

/// The final map points, streamed into static.ply and dynamic.ply as MapCleaner decides them.
class MapFiles : public MapSink {
 public:
  void open(const std::string& dir) {
    static_ = std::make_unique<PlyStreamWriter>(dir + "static.ply");
    dynamic_ = std::make_unique<PlyStreamWriter>(dir + "dynamic.ply");
  }
  void add(const MapPoint& p, bool dynamic) override { (dynamic ? dynamic_ : static_)->add(p); }
  PlyStreamWriter& staticPly() { return *static_; }
  PlyStreamWriter& dynamicPly() { return *dynamic_; }

 private:
  std::unique_ptr<PlyStreamWriter> static_, dynamic_;
};

/// runMapClean()'s state over its passes.
class MapCleanRun {
 public:
  /// Checks the outputs and the files named, opens the input (a chunk: its scans and overlap),
  /// the pose source and the output writers.
  MapCleanRun(const MapCleanOptions& o, const MapCleanProgress& progress);
  /// The one pass: the detector over every scan; each scan mapped backfill_window later.
  void detectAndMap();
  /// The voxel vote, the voxels seen through; the maps written, the writers closed.
  void finish();
  /// SA / DA / AA of the static map against the ground truth (a further pass over the input).
  void score();
  /// A chunk's chunk.ini (last: a folder with it is complete).
  void writeChunkInfo();
  MapCleanSummary& summary() { return sum_; }

 private:
  std::unique_ptr<ScanSource> open() const;
  bool own(std::int64_t t) const { return t >= own_begin_ && t < own_end_; }
  FrameRecord record(const mrptio::FrameResult& fr);
  void mapScan(const Scan& s, const FrameRecord& rec);
  /// The share of the work done when `rec` is mapped (negative: not known).
  double shareDone(const FrameRecord& rec) const;

  const MapCleanOptions& o_;
  const MapCleanProgress& progress_;
  std::string out_;
  std::optional<mrptio::GroundTruth> labels_;  // the classification instead of the detector's
  // A chunk: only its scans are mapped; those of the overlap before and after are read too.
  std::int64_t first_scan_ = 0, own_begin_ = std::numeric_limits<std::int64_t>::min(),
               own_end_ = kNever;
  std::unique_ptr<ScanSource> source_;
  std::unique_ptr<PoseSource> poses_;
  std::unique_ptr<mrptio::SequenceRunner> runner_;
  const mrptio::GroundTruth* gt_labels_ = nullptr;
  MapFiles map_files_;  // before cleaner_, which writes into it
  MapCleaner cleaner_;
  GroundLeveler leveler_;
  std::unique_ptr<CleanedSimplemapWriter> simplemap_;
  std::unique_ptr<KthExporter> exporter_;
  std::unique_ptr<io::TumWriter> tum_, overlap_tum_;  // overlap: a chunk's scans read, not mapped
  std::vector<io::TimedPose> mapped_poses_;           // for the metrics' pass (a few MB per hour)
  std::vector<MapPoint> static_points_;
  std::int64_t last_mapped_ = 0;
  std::size_t scans_read_ = 0;
  bool reached_end_ = false;
  MapCleanSummary sum_;
};

MapCleanRun::MapCleanRun(const MapCleanOptions& o, const MapCleanProgress& progress)
    : o_(o), progress_(progress), out_(o.out_dir + "/"), cleaner_(o.clean, &map_files_) {
  if (!o.overwrite)
    for (const std::string& f : outputFiles(o))
      if (fs::exists(f))
        throw std::runtime_error("output '" + f + "' exists (use -w to replace it)");
  if (!o.labels.empty()) {
    if (o.poses == "ego")
      throw std::runtime_error(
          "--poses ego needs the detector's ego-motion, which does not run with --labels: choose "
          "another pose source");
    if (!fs::is_regular_file(o.labels))
      throw std::runtime_error("label file '" + o.labels + "' does not exist");
    labels_.emplace(o.labels, mrptio::GroundTruth::Options{"label file", false});
  }
  if (o.chunk) {
    o.chunk->validate();
    auto whole = openScanSource(o.input, o.scan_options);
    first_scan_ = firstScanTime(*whole);
    own_begin_ = first_scan_ + nanoseconds(o.chunk->from);
    if (std::isfinite(o.chunk->to)) own_end_ = first_scan_ + nanoseconds(o.chunk->to);
  }
  source_ = open();
  PoseSourceOptions pose_options = o.pose_options;
  pose_options.ego_available = !labels_;
  poses_ = makePoseSource(o.poses, pose_options);
  mrptio::SequenceOptions pass;  // detection, ground truth checked against every scan
  pass.detector = o.detector;
  pass.detect = !labels_;
  pass.single_sensor = true;       // one LiDAR per map
  pass.require_frames = !o.chunk;  // a chunk's range without a scan: said after the pass
  if (!o.ground_truth.empty()) {
    if (!fs::is_regular_file(o.ground_truth))
      throw std::runtime_error("ground truth '" + o.ground_truth + "' does not exist");
    if (!isPcd(o.ground_truth)) pass.ground_truth = o.ground_truth;
  }
  runner_ = std::make_unique<mrptio::SequenceRunner>(*source_, pass);
  gt_labels_ = runner_->groundTruth() ? &*runner_->groundTruth() : nullptr;
  if (o.out_dir.empty()) throw std::runtime_error("no output folder");
  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (!fs::is_directory(o.out_dir))
    throw std::runtime_error("cannot create output directory '" + o.out_dir + "'");
  map_files_.open(out_);
  if (o.formats.simplemap)
    simplemap_ = std::make_unique<CleanedSimplemapWriter>(out_ + "cleaned.simplemap",
                                                          o.keyframe_distance, o.keyframe_angle);
  if (!o.export_kth.empty())
    exporter_ = std::make_unique<KthExporter>(o.export_kth, gt_labels_ != nullptr, o.overwrite);
  tum_ = std::make_unique<io::TumWriter>(out_ + "poses.tum",
                                         "sensor pose in the world, as mapped by dynobj-mapclean");
  if (o.chunk)
    overlap_tum_ = std::make_unique<io::TumWriter>(
        out_ + "overlap.tum", "sensor pose of the scans a dynobj-mapclean chunk read, not mapped");
}

std::unique_ptr<ScanSource> MapCleanRun::open() const {
  auto scans = openScanSource(o_.input, o_.scan_options);
  if (!o_.chunk) return scans;
  const std::int64_t overlap = nanoseconds(o_.chunk->overlap);
  return std::make_unique<TimeWindowSource>(std::move(scans), own_begin_ - overlap,
                                            own_end_ == kNever ? own_end_ : own_end_ + overlap);
}

void MapCleanRun::detectAndMap() {
  // With back-fill, a scan is mapped backfill_window seconds after its detection, read again by
  // a second reader that trails the detector's: memory holds the window's records (no points),
  // never the recording.
  const bool backfill = !labels_ && o_.clean.backfill_window > 0;
  const std::int64_t window = nanoseconds(o_.clean.backfill_window);
  std::unique_ptr<ScanSource> trailing = backfill ? open() : nullptr;
  std::deque<FrameRecord> waiting;
  Scan scan;
  const auto mapOldest = [&] {
    if (!trailing->next(scan) || scan.frame.timestamp_ns != waiting.front().timestamp_ns)
      throw std::runtime_error(source_->describe() + " changed while it was read");
    mapScan(scan, waiting.front());
    waiting.pop_front();
  };
  runner_->run([&](const mrptio::FrameResult& fr) {
    FrameRecord rec = record(fr);
    if (!backfill) return mapScan(fr.frame, rec);
    waiting.push_back(std::move(rec));
    while (waiting.size() > 1 && (waiting.back().timestamp_ns - waiting.front().timestamp_ns >
                                      window ||  // or the clock went back: no waiting on it
                                  waiting.back().timestamp_ns < waiting.front().timestamp_ns))
      mapOldest();
  });
  while (!waiting.empty()) mapOldest();
  sum_.poses = poses_->describe();  // after the first scan: what "auto" chose
  if (!o_.chunk) return;
  reached_end_ = dynamic_cast<const TimeWindowSource&>(*source_).reachedEnd();
  if (sum_.scans == 0)
    throw std::runtime_error("no scan of " + source_->describe() + " from " + o_.chunk->describe() +
                             " after its first scan");
}

FrameRecord MapCleanRun::record(const mrptio::FrameResult& fr) {
  const Scan& s = fr.frame;
  scans_read_++;
  Eigen::Isometry3d pose =
      poses_->pose(s, fr.detection ? fr.detection->ego_motion : core::EgoMotion{});
  if (o_.clean.level_poses)
    if (const auto ground = leveler_.fit(s.frame)) pose = leveler_.level(pose, *ground);
  if (labels_) {
    std::size_t k = 0;
    const io::LabelSweep& sweep = labels_->sweep(s.frame, s.index, &k);
    if (!labels_->labels().isReviewed(k)) sum_.unreviewed_sweeps++;
    return FrameRecord{s.frame.timestamp_ns, pose, sweep.pixels, {}};
  }
  sum_.data_faults.insert(sum_.data_faults.end(), fr.detection->warnings.begin(),
                          fr.detection->warnings.end());
  return cleaner_.record(*fr.detection, pose);
}

void MapCleanRun::mapScan(const Scan& s, const FrameRecord& rec) {
  if (!own(rec.timestamp_ns)) {  // a chunk's overlap: its views count, its points are not mapped
    cleaner_.look(s.frame, rec.sensor_pose);
    overlap_tum_->write(rec.timestamp_ns, rec.sensor_pose);
    (rec.timestamp_ns < own_begin_ ? sum_.scans_before : sum_.scans_after)++;
    return;
  }
  last_mapped_ = rec.timestamp_ns;
  const cv::Mat_<std::uint8_t> mask = cleaner_.dynamicMask(s.frame, rec);
  cleaner_.map(s.frame, mask, rec.sensor_pose);
  if (simplemap_) simplemap_->add(s, mask, rec.sensor_pose);
  if (exporter_) {
    const cv::Mat_<std::uint8_t> gt =
        gt_labels_ ? gt_labels_->mask(s.frame, s.index) : cv::Mat_<std::uint8_t>();
    exporter_->add(s.frame, rec.sensor_pose, gt_labels_ ? &gt : nullptr);
  }
  tum_->write(rec.timestamp_ns, rec.sensor_pose);
  if (!o_.ground_truth.empty()) mapped_poses_.push_back({rec.timestamp_ns, rec.sensor_pose});
  ++sum_.scans;
  if (progress_) progress_("map", sum_.scans, 0, shareDone(rec));
}

double MapCleanRun::shareDone(const FrameRecord& rec) const {
  if (o_.chunk && own_end_ != kNever) {  // a chunk with an end: of its time span
    const double begin = static_cast<double>(own_begin_) - 1e9 * o_.chunk->overlap;
    const double end = static_cast<double>(own_end_) + 1e9 * o_.chunk->overlap;
    return std::clamp((static_cast<double>(rec.timestamp_ns) - begin) / (end - begin), 0.0, 1.0);
  }
  // Of the input's bytes: as many as read so far, times the scans mapped of those read (the
  // mapping trails the reading).
  const double read = source_->progress();  // negative: not known
  if (read < 0) return -1;
  return std::min(1.0, read * static_cast<double>(sum_.scans + sum_.scans_before) /
                           static_cast<double>(std::max<std::size_t>(1, scans_read_)));
}

void MapCleanRun::finish() {
  cleaner_.finish();
  PlyStreamWriter &st = map_files_.staticPly(), &dy = map_files_.dynamicPly();
  st.finish();
  dy.finish();
  sum_.voted = cleaner_.voted();
  sum_.seen_through = cleaner_.seenThrough();
  sum_.points_static = cleaner_.staticMap().pointsInserted();
  sum_.points_dynamic = cleaner_.dynamicMap().pointsInserted();
  sum_.map_static = st.count();
  sum_.map_dynamic = dy.count();
  sum_.peak_voxels = cleaner_.peakVoxels();
  sum_.backfilled = cleaner_.backfilledPixels();
  sum_.confirmed_tracks = cleaner_.confirmedTracks().size();
  // The other formats and the metrics need the whole map: read back from the streamed files.
  MapFormats rest = o_.formats;
  rest.ply = false;
  std::vector<MapPoint> dynamic_points;
  if (rest.png || rest.pointsmap || rest.txt || !o_.ground_truth.empty())
    static_points_ = readPly(st.partialPath());
  if (rest.png || rest.pointsmap || rest.txt) dynamic_points = readPly(dy.partialPath());
  if (o_.formats.ply) {
    st.commit();
    dy.commit();
    sum_.files = {out_ + "static.ply", out_ + "dynamic.ply"};
  }
  for (const std::string& f :
       writeMaps(o_.out_dir, rest, static_points_, dynamic_points, o_.png_resolution))
    sum_.files.push_back(f);
  tum_->close();
  sum_.files.push_back(out_ + "poses.tum");
  if (simplemap_) {
    simplemap_->close();
    sum_.keyframes = simplemap_->keyframes();
    sum_.files.push_back(out_ + "cleaned.simplemap");
  }
  if (exporter_) {
    exporter_->close();
    sum_.exported_frames = exporter_->frames();
    sum_.exported_points = exporter_->points();
    sum_.files.push_back(o_.export_kth);
  }
  if (overlap_tum_) {
    overlap_tum_->close();
    sum_.files.push_back(out_ + "overlap.tum");
  }
}

void MapCleanRun::score() {
  source_->rewind();
  sum_.scores = scoreMap(static_points_, o_.tolerance, source_.get(), gt_labels_, o_.ground_truth,
                         mapped_poses_, o_.clean.min_range, progress_);
}

void MapCleanRun::writeChunkInfo() {
  ChunkInfo info;
  info.input = o_.input;
  info.first_scan_ns = first_scan_;
  info.range = *o_.chunk;
  info.scans = sum_.scans;
  info.scans_before = sum_.scans_before;
  info.scans_after = sum_.scans_after;
  info.reached_end = reached_end_;
  info.last_scan = 1e-9 * static_cast<double>(last_mapped_ - first_scan_);
  info.voxel_size = o_.clean.voxel_size;
  info.dynamic_vote = o_.clean.dynamic_vote;
  info.min_range = o_.clean.min_range;
  info.poses = sum_.poses;
  info.formats = o_.formats.toString();
  info.write(sum_.files.emplace_back(out_ + "chunk.ini"));
}

}  // namespace

MapCleanSummary runMapClean(const MapCleanOptions& o, const MapCleanProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  MapCleanRun run(o, progress);
  run.detectAndMap();                        // detect, map (with the back-fill), count the views
  run.finish();                              // vote, seen through; the maps written
  if (!o.ground_truth.empty()) run.score();  // metrics: the final static map against the truth
  if (o.chunk) run.writeChunkInfo();
  MapCleanSummary& sum = run.summary();
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sum;
}

}  // namespace dynobj::mapclean
