// SPDX-License-Identifier: BSD-3-Clause
// The text dynobj-mapclean prints after a job, and after a merge of chunks.
#include <dynobj/core/FrameCheck.h>

#include <cstdarg>
#include <cstdio>
#include <map>
#include <string>

#include "dynobj/mapclean/ChunkMerge.h"
#include "dynobj/mapclean/MapCleanJob.h"

namespace dynobj::mapclean {
namespace {

std::string fmt(const char* format, ...) {
  va_list args, again;
  va_start(args, format);
  va_copy(again, args);
  std::string b(static_cast<std::size_t>(std::vsnprintf(nullptr, 0, format, args)) + 1, '\0');
  va_end(args);
  std::vsnprintf(b.data(), b.size(), format, again);
  va_end(again);
  b.pop_back();
  return b;
}

std::string pct(const std::optional<double>& v) {
  if (!v) return "n/a";
  char b[32];
  std::snprintf(b, sizeof(b), "%.2f%%", 100.0 * *v);
  return b;
}

std::string scoresText(const MapScores& m, double tolerance) {
  return fmt(
      "  SA %s  DA %s  AA %s  ghost points %zu  (GT static %zu kept %zu, GT dynamic %zu removed "
      "%zu, tolerance %.3f m)\n",
      pct(m.sa()).c_str(), pct(m.da()).c_str(), pct(m.aa()).c_str(), m.ghost_points, m.gt_static,
      m.static_kept, m.gt_dynamic, m.dynamic_removed, tolerance);
}

}  // namespace

std::string summaryText(const MapCleanSummary& s, const MapCleanOptions& o) {
  std::string out;
  const std::string backfill = o.clean.backfill_window > 0 && o.labels.empty()
                                   ? fmt("back-fill window %.3g s", o.clean.backfill_window)
                                   : std::string("no back-fill");
  out += fmt("dynobj-mapclean: %zu scans, poses: %s%s, %s\n", s.scans, s.poses.c_str(),
             o.clean.level_poses ? " (leveled with the floor)" : "", backfill.c_str());
  if (o.chunk)
    out +=
        fmt("  chunk %s after the first scan; read besides: %zu scans before, %zu after "
            "(overlap %.3g s)\n",
            o.chunk->describe().c_str(), s.scans_before, s.scans_after, o.chunk->overlap);
  if (!o.labels.empty())
    out += fmt(
        "  classification: label file '%s' (detector not run; %zu scans by unreviewed sweeps)\n",
        o.labels.c_str(), s.unreviewed_sweeps);
  if (!s.data_faults.empty()) {
    std::map<core::FrameFault, std::size_t> counts;
    for (const core::FrameWarning& w : s.data_faults) {
      out += "  warning: " + w.text() + "\n";
      counts[w.fault]++;
    }
    out += "  data faults: " + core::faultCounts(counts) + "\n";
  }
  out += fmt(
      "  static map %zu points (from %zu), dynamic map %zu points (from %zu); %zu tracks confirmed "
      "dynamic, %zu points added by the back-fill, %zu voxels by the vote, %zu by the free-space "
      "check; at most %zu voxels in memory\n",
      s.map_static, s.points_static, s.map_dynamic, s.points_dynamic, s.confirmed_tracks,
      s.backfilled, s.voted, s.seen_through, s.peak_voxels);
  if (o.formats.simplemap) out += fmt("  cleaned simplemap: %zu keyframes\n", s.keyframes);
  if (!o.export_kth.empty())
    out += fmt("  KTH export: %zu frames, %zu points -> %s\n", s.exported_frames, s.exported_points,
               o.export_kth.c_str());
  if (s.scores) out += scoresText(*s.scores, o.tolerance);
  out += fmt("  %.1f s -> %s\n", s.seconds, o.out_dir.c_str());
  return out;
}

std::string mergeSummaryText(const MergeSummary& s, const MergeOptions& o) {
  std::string out = fmt("dynobj-mapclean --merge: %zu chunks, %zu scans, poses: %s\n", s.chunks,
                        s.scans, s.poses.c_str());
  if (!s.seam_gap.empty()) {
    out += "  seams (largest distance between two chunks' positions of the scans both read):";
    for (const double g : s.seam_gap) out += fmt(" %.3f m", g);
    out += "\n";
  }
  out += fmt("  static map %zu points, dynamic map %zu points; %zu voxels by the vote\n",
             s.map_static, s.map_dynamic, s.voted);
  if (o.formats.simplemap) out += fmt("  cleaned simplemap: %zu keyframes\n", s.keyframes);
  if (s.scores) out += scoresText(*s.scores, o.tolerance);
  out += fmt("  %.1f s -> %s\n", s.seconds, o.out_dir.c_str());
  return out;
}

}  // namespace dynobj::mapclean
