// SPDX-License-Identifier: BSD-3-Clause
// A long recording cleaned in chunks (dynobj-mapclean --chunk-from/--chunk-to, one process each,
// e.g. under GNU parallel or a Slurm array) and merged into one map (dynobj-mapclean --merge):
//  - planChunks(): the chunks' time ranges, cut at scans, each about `length` seconds;
//  - each chunk's folder holds its maps, poses.tum (its own scans), overlap.tum (the scans it read
//    before and after them) and chunk.ini (ChunkInfo);
//  - mergeChunks(): checks that the chunks are of one input and cover it without gap or overlap,
//    places chunk k in chunk 0's world by the pose both give to the last scan before chunk k's
//    range (chunk k-1's own, chunk k's overlap: its ego-motion started elsewhere), puts every
//    chunk's map points into one static and one dynamic voxel map (a voxel shared by chunks: the
//    mean of their points), votes as one run does (MapCleaner's voteVoxels), writes the maps,
//    poses.tum and (when every chunk has one) cleaned.simplemap.
// A chunk's free-space check sees its own scans and its overlap's only: an object that stays for
// longer than a chunk and its overlap and then leaves remains in the merged static map (docs/
// mapclean.md "Long recordings in chunks" gives the measured difference to one run).
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "dynobj/mapclean/MapCleanJob.h"

namespace dynobj::mapclean {

/// chunk.ini, section [chunk]: what mergeChunks() needs to know of a chunk.
struct ChunkInfo {
  std::string input;               ///< as given to dynobj-mapclean -i
  std::int64_t first_scan_ns = 0;  ///< the input's first scan: the chunks' common time origin
  ChunkRange range;
  std::size_t scans = 0;                          ///< mapped (from <= t < to)
  std::size_t scans_before = 0, scans_after = 0;  ///< read in the overlap, not mapped
  bool reached_end = false;  ///< the input ended before the range and its overlap did
  double last_scan = 0;      ///< [s] the last mapped scan's time since first_scan_ns
  double voxel_size = 0, dynamic_vote = 0, min_range = 0;  ///< [mapclean] of the run
  std::string poses;                                       ///< the pose source's description
  std::string formats;                                     ///< MapFormats::toString() of the run

  /// Writes chunk.ini atomically.
  void write(const std::string& path) const;
  /// Throws std::runtime_error naming the file and the missing or bad key.
  static ChunkInfo read(const std::string& path);
};

/// Chunks of about `length` seconds over `input`'s scans (read for their times only): [from, to)
/// pairs since the first scan, each starting at a scan; the last one's `to` is infinite.
std::vector<std::pair<double, double>> planChunks(const std::string& input,
                                                  const ScanSourceOptions& scan_options,
                                                  double length);

struct MergeOptions {
  std::vector<std::string> chunks;  ///< chunk folders, any order
  std::string out_dir;
  bool overwrite = false;
  MapFormats formats;  ///< ply needed in every chunk; simplemap merged if every chunk has it
  double png_resolution = 0.05;
  /// Scores of the merged map as runMapClean() gives them (needs `input` for a label file v1).
  std::string ground_truth;
  std::string input;
  ScanSourceOptions scan_options;
  double tolerance = 0.05;  ///< [m]
};

struct MergeSummary {
  std::size_t chunks = 0, scans = 0;
  std::size_t map_static = 0, map_dynamic = 0, voted = 0;
  std::string poses;  ///< the chunks' pose source
  /// Per seam between chunk k-1 and k: the largest distance [m] between the two chunks' positions
  /// of the scans both read after the seam (chunk k-1's overlap, chunk k's own), once aligned.
  std::vector<double> seam_gap;
  std::size_t keyframes = 0;
  std::optional<MapScores> scores;
  double seconds = 0;
  std::vector<std::string> files;
};

/// Merges the chunks into opts.out_dir. Throws std::runtime_error naming the chunk and the problem:
/// a missing or bad chunk.ini or map, chunks of other inputs or voxel sizes, a gap or an overlap
/// between two ranges, a range no scan of which was read, a first chunk that does not start at 0
/// or a last one that does not reach the end, chunks without a shared scan to align them; and when
/// an output exists unless opts.overwrite.
MergeSummary mergeChunks(const MergeOptions& opts, const MapCleanProgress& progress = {});

/// What dynobj-mapclean --merge prints.
std::string mergeSummaryText(const MergeSummary& summary, const MergeOptions& opts);

}  // namespace dynobj::mapclean
