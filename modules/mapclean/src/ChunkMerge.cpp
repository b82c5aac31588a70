// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/ChunkMerge.h"

#include <dynobj/core/Config.h>
#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/IniFile.h>
#include <dynobj/io/PoseFile.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "dynobj/mapclean/MrptOutputs.h"
#include "dynobj/mapclean/PointCloudIO.h"
#include "dynobj/mapclean/VoxelMap.h"

namespace dynobj::mapclean {
namespace {

namespace fs = std::filesystem;

std::string seconds(double s) {
  if (!std::isfinite(s)) return "end";
  char b[40];
  std::snprintf(b, sizeof(b), "%.9g", s);
  return b;
}

/// A chunk's poses file; none when it holds no pose (a chunk without scans on that side).
std::vector<io::TimedPose> readPoses(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("chunk file '" + path + "' is missing");
  std::string line;
  bool any = false;
  while (!any && std::getline(in, line))
    any = line.find_first_not_of(" \t\r") != std::string::npos && line[0] != '#';
  if (!any) return {};
  return io::readPoseFile(path, io::PoseFormat::Tum);
}

constexpr std::int64_t kSameScanNs = 100000;  // 0.1 ms: two files' times of one scan

struct Chunk {
  std::string dir;
  ChunkInfo info;
  Eigen::Isometry3d to_world = Eigen::Isometry3d::Identity();  ///< into chunk 0's world
};

}  // namespace

void ChunkInfo::write(const std::string& path) const {
  io::AtomicFile f(path);
  auto& o = f.stream();
  o << "# A chunk of dynobj-mapclean --chunk-from/--chunk-to: what dynobj-mapclean --merge "
       "reads\n[chunk]\n"
    << "input = " << input << "\nfirst_scan_ns = " << first_scan_ns
    << "\nfrom = " << seconds(range.from) << "\nto = " << seconds(range.to)
    << "\noverlap = " << seconds(range.overlap) << "\nscans = " << scans
    << "\nscans_before = " << scans_before << "\nscans_after = " << scans_after
    << "\nreached_end = " << (reached_end ? "true" : "false")
    << "\nlast_scan = " << seconds(last_scan) << "\nvoxel_size = " << seconds(voxel_size)
    << "\ndynamic_vote = " << seconds(dynamic_vote) << "\nmin_range = " << seconds(min_range)
    << "\nposes = " << poses << "\nformats = " << formats << "\n";
  f.commit();
}

ChunkInfo ChunkInfo::read(const std::string& path) {
  io::IniFile ini(path, "chunk file");
  const std::vector<std::string> keys = {
      "input",      "first_scan_ns", "from",        "to",          "overlap",
      "scans",      "scans_before",  "scans_after", "reached_end", "last_scan",
      "voxel_size", "dynamic_vote",  "min_range",   "poses",       "formats"};
  ini.expect("chunk", keys);
  ini.check();
  const auto& cfg = ini.config();
  const auto text = [&](const char* key) { return core::readString(cfg, "chunk", key, "", true); };
  const auto number = [&](const char* key) {
    const std::string v = text(key);
    if (v == "end") return std::numeric_limits<double>::infinity();
    return core::readDouble(cfg, "chunk", key, 0, true);
  };
  const auto count = [&](const char* key) {
    return static_cast<std::size_t>(core::readDouble(cfg, "chunk", key, 0, true));
  };
  ChunkInfo c;
  c.input = text("input");
  try {
    c.first_scan_ns = std::stoll(text("first_scan_ns"));
  } catch (const std::exception&) {
    throw std::runtime_error(path + ": first_scan_ns is not a time in nanoseconds");
  }
  c.range.from = number("from");
  c.range.to = number("to");
  c.range.overlap = number("overlap");
  c.scans = count("scans");
  c.scans_before = count("scans_before");
  c.scans_after = count("scans_after");
  c.reached_end = core::readBool(cfg, "chunk", "reached_end", false, true);
  c.last_scan = number("last_scan");
  c.voxel_size = number("voxel_size");
  c.dynamic_vote = number("dynamic_vote");
  c.min_range = number("min_range");
  c.poses = text("poses");
  c.formats = text("formats");
  return c;
}

std::vector<std::pair<double, double>> planChunks(const std::string& input,
                                                  const ScanSourceOptions& scan_options,
                                                  double length) {
  if (!(length > 0) || !std::isfinite(length))
    throw std::invalid_argument("the chunk length must be > 0 s");
  auto source = openScanSource(input, scan_options);
  std::vector<std::pair<double, double>> chunks;
  std::int64_t t = 0, first = 0;
  bool any = false;
  while (source->nextTime(t)) {
    if (!any) first = t;
    any = true;
    const double since = 1e-9 * static_cast<double>(t - first);
    if (chunks.empty() || since - chunks.back().first >= length) {
      if (!chunks.empty()) chunks.back().second = since;
      chunks.emplace_back(since, std::numeric_limits<double>::infinity());
    }
  }
  if (!any)
    throw std::runtime_error("no LiDAR scan in " + source->describe() + source->noFramesDetail());
  return chunks;
}

MergeSummary mergeChunks(const MergeOptions& o, const MapCleanProgress& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  if (o.chunks.empty()) throw std::runtime_error("--merge: no chunk folder given");
  const bool gt_labels = !o.ground_truth.empty() && fs::path(o.ground_truth).extension() != ".pcd";
  if (!o.ground_truth.empty() && !fs::is_regular_file(o.ground_truth))
    throw std::runtime_error("ground truth '" + o.ground_truth + "' does not exist");
  if (gt_labels && o.input.empty())
    throw std::runtime_error("--gt with a label file needs the chunks' input (-i) for its scans");
  MapCleanOptions as_run;  // the merged folder holds what one run writes
  as_run.out_dir = o.out_dir;
  as_run.formats = o.formats;
  if (!o.overwrite)
    for (const std::string& f : outputFiles(as_run))
      if (fs::exists(f))
        throw std::runtime_error("output '" + f + "' exists (use -w to replace it)");

  std::vector<Chunk> chunks;
  for (const std::string& dir : o.chunks) {
    const std::string ini = dir + "/chunk.ini";
    if (!fs::is_regular_file(ini))
      throw std::runtime_error("'" + dir +
                               "' is not a dynobj-mapclean chunk (no chunk.ini: chunks are made "
                               "with --chunk-from/--chunk-to)");
    chunks.push_back({dir, ChunkInfo::read(ini)});
  }
  std::sort(chunks.begin(), chunks.end(),
            [](const Chunk& a, const Chunk& b) { return a.info.range.from < b.info.range.from; });
  const ChunkInfo& first = chunks.front().info;
  if (first.range.from > 1e-9)
    throw std::runtime_error(
        "the first chunk, '" + chunks.front().dir + "', starts at " + seconds(first.range.from) +
        " s: the scans before are in no chunk (the first starts at --chunk-from 0)");
  for (std::size_t k = 0; k < chunks.size(); k++) {
    const Chunk& c = chunks[k];
    const auto differ = [&](const std::string& what) {
      return std::runtime_error("chunk '" + c.dir + "' and '" + chunks.front().dir +
                                "' differ in " + what + ": chunks of one run are merged");
    };
    if (c.info.first_scan_ns != first.first_scan_ns) throw differ("their input (first scan)");
    if (c.info.voxel_size != first.voxel_size) throw differ("voxel_size");
    if (c.info.dynamic_vote != first.dynamic_vote) throw differ("dynamic_vote");
    if (c.info.min_range != first.min_range) throw differ("min_range");
    if (c.info.poses != first.poses) throw differ("pose source");
    if (k == 0) continue;
    const ChunkInfo& prev = chunks[k - 1].info;
    const double seam = c.info.range.from;
    if (std::abs(prev.range.to - seam) > 1e-6)
      throw std::runtime_error(
          std::string(prev.range.to < seam ? "a gap" : "an overlap") + " between chunk '" +
          chunks[k - 1].dir + "' (to " + seconds(prev.range.to) + " s) and '" + c.dir + "' (from " +
          seconds(seam) + " s): each chunk must start where the one before ends");
  }
  const ChunkInfo& last = chunks.back().info;
  if (std::isfinite(last.range.to) && !(last.reached_end && last.scans_after == 0))
    throw std::runtime_error("the last chunk, '" + chunks.back().dir + "', ends at " +
                             seconds(last.range.to) +
                             " s, before the input: the scans after it are in no chunk (the last "
                             "chunk goes --chunk-to end)");
  for (const Chunk& c : chunks) {
    for (const char* name : {"static.ply", "dynamic.ply"})
      if (!fs::is_regular_file(c.dir + "/" + name))
        throw std::runtime_error("chunk '" + c.dir + "' has no " + name +
                                 " (its --formats must include ply)");
    if (o.formats.simplemap && !fs::is_regular_file(c.dir + "/cleaned.simplemap"))
      throw std::runtime_error("chunk '" + c.dir +
                               "' has no cleaned.simplemap: merge with --formats without "
                               "simplemap, or make the chunks with it");
  }

  MergeSummary sum;
  sum.chunks = chunks.size();
  sum.poses = first.poses;
  // Chunk k in chunk 0's world: by the last scan before chunk k's range, which chunk k-1 mapped
  // and chunk k read in its overlap.
  std::vector<std::vector<io::TimedPose>> own(chunks.size()), overlap(chunks.size());
  for (std::size_t k = 0; k < chunks.size(); k++) {
    own[k] = readPoses(chunks[k].dir + "/poses.tum");
    overlap[k] = readPoses(chunks[k].dir + "/overlap.tum");
    sum.scans += own[k].size();
  }
  for (std::size_t k = 1; k < chunks.size(); k++) {
    const std::int64_t seam =
        first.first_scan_ns +
        static_cast<std::int64_t>(std::llround(chunks[k].info.range.from * 1e9));
    const io::TimedPose* mine = nullptr;
    const io::TimedPose* theirs = nullptr;
    for (const io::TimedPose& p : overlap[k])
      if (p.timestamp_ns < seam)
        if (const io::TimedPose* q = io::findPose(own[k - 1], p.timestamp_ns, kSameScanNs)) {
          mine = &p;
          theirs = q;
        }
    if (!mine)
      throw std::runtime_error("chunk '" + chunks[k].dir + "' shares no scan with '" +
                               chunks[k - 1].dir +
                               "' to align them (its overlap read none of "
                               "the scans before " +
                               seconds(chunks[k].info.range.from) + " s)");
    chunks[k].to_world = chunks[k - 1].to_world * theirs->pose * mine->pose.inverse();
    double gap = 0;  // the scans after the seam, placed by both chunks
    for (const io::TimedPose& p : overlap[k - 1])
      if (p.timestamp_ns >= seam)
        if (const io::TimedPose* q = io::findPose(own[k], p.timestamp_ns, kSameScanNs))
          gap = std::max(gap, ((chunks[k - 1].to_world * p.pose).translation() -
                               (chunks[k].to_world * q->pose).translation())
                                  .norm());
    sum.seam_gap.push_back(gap);
  }

  VoxelMap st(first.voxel_size), dy(first.voxel_size);
  for (std::size_t k = 0; k < chunks.size(); k++) {
    const Eigen::Matrix3f R = chunks[k].to_world.linear().cast<float>();
    const Eigen::Vector3f t = chunks[k].to_world.translation().cast<float>();
    for (auto [name, map] : {std::pair{"/static.ply", &st}, std::pair{"/dynamic.ply", &dy}})
      for (const MapPoint& p : readPly(chunks[k].dir + name)) {
        const Eigen::Vector3f w = R * Eigen::Vector3f(p.x, p.y, p.z) + t;
        map->insert({w.x(), w.y(), w.z(), p.intensity});
      }
    if (progress)
      progress("merge", k + 1, chunks.size(),
               static_cast<double>(k + 1) / static_cast<double>(chunks.size()));
  }
  sum.voted = voteVoxels(st, dy, first.dynamic_vote);

  std::error_code ec;
  fs::create_directories(o.out_dir, ec);
  if (!fs::is_directory(o.out_dir))
    throw std::runtime_error("cannot create output directory '" + o.out_dir + "'");
  const std::vector<MapPoint> st_points = st.points(), dy_points = dy.points();
  sum.map_static = st_points.size();
  sum.map_dynamic = dy_points.size();
  sum.files = writeMaps(o.out_dir, o.formats, st_points, dy_points, o.png_resolution);
  io::TumWriter tum(o.out_dir + "/poses.tum",
                    "sensor pose in the world, as mapped by dynobj-mapclean");
  std::vector<io::TimedPose> poses;
  for (std::size_t k = 0; k < chunks.size(); k++)
    for (const io::TimedPose& p : own[k]) {
      poses.push_back({p.timestamp_ns, chunks[k].to_world * p.pose});
      tum.write(p.timestamp_ns, poses.back().pose);
    }
  tum.close();
  sum.files.push_back(o.out_dir + "/poses.tum");
  if (o.formats.simplemap) {
    std::vector<std::pair<std::string, Eigen::Isometry3d>> parts;
    for (const Chunk& c : chunks) parts.emplace_back(c.dir + "/cleaned.simplemap", c.to_world);
    sum.keyframes = mergeSimplemaps(parts, o.out_dir + "/cleaned.simplemap");
    sum.files.push_back(o.out_dir + "/cleaned.simplemap");
  }
  if (!o.ground_truth.empty()) {
    std::unique_ptr<ScanSource> scans;
    std::optional<mrptio::GroundTruth> labels;
    if (gt_labels) {
      scans = openScanSource(o.input, o.scan_options);
      if (firstScanTime(*scans) != first.first_scan_ns)
        throw std::runtime_error("-i '" + o.input +
                                 "' is not the chunks' input (its first scan "
                                 "differs)");
      labels.emplace(o.ground_truth);
    }
    sum.scores = scoreMap(st_points, o.tolerance, scans.get(), labels ? &*labels : nullptr,
                          o.ground_truth, poses, first.min_range, progress);
  }
  sum.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return sum;
}

}  // namespace dynobj::mapclean
