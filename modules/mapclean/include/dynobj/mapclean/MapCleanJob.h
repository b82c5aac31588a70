// SPDX-License-Identifier: BSD-3-Clause
// dynobj-mapclean's whole job in one pass over the input (memory grows with the map, not with the
// number of scans):
//   detect: the detector over every scan (or, with `labels`, the label file's sweep of each scan:
//           the detector is not run), the pose of each scan (FrameRecord: no points kept);
//   map:    each scan backfill_window seconds later (read again by a trailing reader; at once
//           without back-fill): dynamic = detector + the boxes of tracks confirmed by then, into
//           the static / dynamic voxel maps (with its free-space views of the map so far), the
//           cleaned simplemap, the KTH export and poses.tum; the voxels final by then (vote,
//           free-space rule) streamed to static / dynamic .ply;
//   finish: the same for the voxels left; .pointsmap, .txt, top-down PNGs from the PLYs read
//           back, cleaned .simplemap;
//   metrics (with ground truth only, a further pass after the map is final): SA / DA / AA.
// Every output file is written as *.partial and renamed when complete; on an error nothing that
// looks complete is left behind.
#pragma once

#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/GroundTruth.h>

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "dynobj/mapclean/MapCleaner.h"
#include "dynobj/mapclean/MapMetrics.h"
#include "dynobj/mapclean/PoseSource.h"
#include "dynobj/mapclean/ScanSource.h"

namespace dynobj::mapclean {

/// Which outputs runMapClean() writes (--formats); poses.tum is always written.
struct MapFormats {
  bool ply = true;         ///< static.ply, dynamic.ply (binary PLY: the compact map format)
  bool pointsmap = false;  ///< static.pointsmap, dynamic.pointsmap (serialized CPointsMapXYZI)
  bool txt = false;        ///< static.txt, dynamic.txt (x y z intensity text)
  bool png = true;         ///< map.png, static.png (top views with legend and scale bar)
  bool simplemap = true;   ///< cleaned.simplemap (keyframes for MRPT's map tools)

  /// A comma-separated list of the names above, or "all". Throws std::invalid_argument naming
  /// an unknown or missing name: `--formats: unknown format 'pyl' (did you mean 'ply'?)`.
  static MapFormats parse(const std::string& list);
  std::string toString() const;  ///< "ply,png,simplemap"
};

/// A chunk of a long recording (dynobj-mapclean --chunk-from/--chunk-to; docs/mapclean.md "Long
/// recordings in chunks"): only the scans from `from` to `to` seconds after the input's first scan
/// are mapped; the `overlap` seconds before and after are read too, for the detector's warm-up, the
/// free-space views and the back-fill, and their poses let mergeChunks() align the chunks. The
/// output folder also gets chunk.ini (ChunkInfo) and overlap.tum (the poses of the scans read but
/// not mapped).
struct ChunkRange {
  double from = 0.0;                                    ///< [s] since the input's first scan
  double to = std::numeric_limits<double>::infinity();  ///< [s] (excluded); inf = the end
  double overlap = 30.0;                                ///< [s] > 0
  /// Throws std::invalid_argument naming --chunk-from, --chunk-to or --chunk-overlap.
  void validate() const;
  /// "60 s to 120 s", "120 s to the end".
  std::string describe() const;
};

struct MapCleanOptions {
  std::string input;           ///< .rawlog or a KTH DynamicMap folder
  std::string out_dir;         ///< created if missing
  std::string poses = "auto";  ///< PoseSource spec ("auto": odometry, else viewpoint, else ego)
  bool overwrite = false;      ///< replace earlier outputs in out_dir (else they are an error)
  PoseSourceOptions pose_options;
  ScanSourceOptions scan_options;
  core::DetectorParams detector;
  MapCleanParams clean;
  /// Label file v1 (e.g. dynobj-label's): its sweep of each scan is the classification, instead
  /// of the detector's (no back-fill then); "" = run the detector. Every scan must have
  /// its sweep (matched by timestamp, same image size). Not with poses "ego".
  std::string labels;
  std::string ground_truth;  ///< label file v1 (rawlog input) or a labelled gt_cloud.pcd; "" = none
  double tolerance = 0.05;   ///< [m] metric: a GT point is kept when a map point is this close
  std::string export_kth;    ///< folder for the KTH export; "" = none
  MapFormats formats;
  double keyframe_distance = 1.0;               ///< [m] cleaned simplemap keyframes
  double keyframe_angle = 30.0 * M_PI / 180.0;  ///< [rad]
  double png_resolution = 0.05;                 ///< [m/px]
  std::optional<ChunkRange> chunk;              ///< map only this chunk (none: the whole input)
};

struct MapCleanSummary {
  std::size_t scans = 0;
  std::size_t points_static = 0, points_dynamic = 0;  ///< scan points sent to each map
  std::size_t map_static = 0, map_dynamic = 0;        ///< map points (voxels)
  std::size_t peak_voxels = 0;   ///< most voxels in memory at once (final_after)
  std::size_t voted = 0;         ///< static voxels moved to the dynamic map by the voxel vote
  std::size_t seen_through = 0;  ///< static voxels moved by the free-space check
  std::size_t backfilled = 0, confirmed_tracks = 0, keyframes = 0, exported_frames = 0,
              exported_points = 0;
  std::optional<MapScores> scores;
  std::string poses;                  ///< description of the pose source
  std::size_t unreviewed_sweeps = 0;  ///< with labels: scans classified by unreviewed sweeps
  std::vector<core::FrameWarning> data_faults;  ///< the detector's (core::FrameCheck), in order
  double seconds = 0;
  std::vector<std::string> files;                 ///< written
  std::size_t scans_before = 0, scans_after = 0;  ///< a chunk's scans read but not mapped
};

/// stage ("map", "evaluate", "merge"), scans (chunks) done, their total (0 when not known yet),
/// and the share of the stage's work done (0-1; negative when not known): of the input read
/// (a chunk: of its time range and overlap), for estimates of the time left.
using MapCleanProgress =
    std::function<void(const char* stage, std::size_t done, std::size_t total, double fraction)>;

/// What dynobj-mapclean prints: scans, pose source, the data faults (one line each, and their
/// counts), map sizes, simplemap, export, metrics, time.
std::string summaryText(const MapCleanSummary& summary, const MapCleanOptions& opts);

/// The files runMapClean() writes into opts.out_dir (and the KTH export folder).
std::vector<std::string> outputFiles(const MapCleanOptions& opts);

/// Writes the maps' files that `formats` asks for into `out_dir` (static / dynamic .ply,
/// .pointsmap, .txt; map.png and static.png with legend and scale bar at `png_resolution` m/px):
/// what runMapClean() and mergeChunks() write. Returns the files written.
std::vector<std::string> writeMaps(const std::string& out_dir, const MapFormats& formats,
                                   const std::vector<MapPoint>& static_points,
                                   const std::vector<MapPoint>& dynamic_points,
                                   double png_resolution);

/// SA / DA / AA of `static_points` (MapEvaluator, `tolerance` m): against the points of `scans`
/// labelled by `labels`, each scan placed with its pose in `poses` (in the scans' order, matched by
/// time; scans without one are not scored), or, without `labels`, against the labelled cloud
/// `gt_pcd`.
MapScores scoreMap(const std::vector<MapPoint>& static_points, double tolerance, ScanSource* scans,
                   const mrptio::GroundTruth* labels, const std::string& gt_pcd,
                   const std::vector<io::TimedPose>& poses, double min_range,
                   const MapCleanProgress& progress);

/// Runs the job. Throws std::runtime_error (naming the file / scan) on any bad input, and when an
/// output exists already unless opts.overwrite.
MapCleanSummary runMapClean(const MapCleanOptions& opts, const MapCleanProgress& progress = {});

}  // namespace dynobj::mapclean
