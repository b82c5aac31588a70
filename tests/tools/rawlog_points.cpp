// SPDX-License-Identifier: BSD-3-Clause
// Test tool: checks what rawlog-dynobj did to the LiDAR points of a rawlog, from the raw MRPT
// objects (not through the project's converters). LiDAR observations are paired by entry and by
// order within the entry; "<label>_DYNAMIC" point clouds (split mode) are matched to the scan
// before them. Exit code 0 when the check holds, 1 with the first difference otherwise.
//
//   rawlog_points partition <in> <out> [labels] [sensor-label]
//       every output scan's points are the input scan's minus the removed ones (exact multiset
//       of coordinates); split clouds hold exactly the removed points; stock map insertion of the
//       output reads exactly the kept points. With a label file (v1) and organized range scans:
//       the removed points are exactly those on the labelled pixels (with a return), their ranges
//       moved into the "dynamic" layer; other scans (Velodyne, point clouds: no pixel per point in
//       the raw object) removed as many points as their sweep labels pixels. `sensor-label`: only
//       that sensor's scans read the labels.
//   rawlog_points marked <in> <out> <labels>
//       mark mode: geometry byte-identical, the pixelLabels bit "dynamic" set on exactly the
//       labelled pixels of each sweep.
//   rawlog_points same-removal <in_a> <out_a> <in_b> <out_b>
//       two recordings of the same sweeps filtered alike: each scan lost the same points in both.
//   rawlog_points same <a> <b>
//       restore: every range image identical, no "dynamic" layer left, the same number of points
//       and each pixel's point within 1 mm of the original's (restored points are re-created on
//       their pixel's ray).
#include <dynobj/io/LabelFile.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <mrpt/maps/CSimplePointsMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <string>

namespace {

using namespace mrpt::obs;
using P3 = std::array<float, 3>;

struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

bool isLidar(const CObservation& o) {
  return IS_CLASS(o, CObservation3DRangeScan) || IS_CLASS(o, CObservationVelodyneScan) ||
         IS_CLASS(o, CObservationPointCloud);
}

bool isSplit(const CObservation& o) {
  const std::string& l = o.sensorLabel;
  return IS_CLASS(o, CObservationPointCloud) && l.size() > 8 &&
         l.compare(l.size() - 8, 8, "_DYNAMIC") == 0;
}

/// The points a LiDAR observation holds, in its own (sensor) frame.
std::vector<P3> pointsOf(const CObservation& o) {
  std::vector<P3> p;
  if (const auto* s = dynamic_cast<const CObservation3DRangeScan*>(&o)) {
    for (std::size_t i = 0; i < s->points3D_x.size(); i++)
      p.push_back({s->points3D_x[i], s->points3D_y[i], s->points3D_z[i]});
  } else if (const auto* v = dynamic_cast<const CObservationVelodyneScan*>(&o)) {
    CObservationVelodyneScan copy(*v);
    if (copy.point_cloud.size() == 0) copy.generatePointCloud();
    for (std::size_t i = 0; i < copy.point_cloud.size(); i++)
      p.push_back({copy.point_cloud.x[i], copy.point_cloud.y[i], copy.point_cloud.z[i]});
  } else if (const auto* c = dynamic_cast<const CObservationPointCloud*>(&o)) {
    if (c->pointcloud)
      for (std::size_t i = 0; i < c->pointcloud->size(); i++) {
        float x, y, z;
        c->pointcloud->getPoint(i, x, y, z);
        p.push_back({x, y, z});
      }
  }
  return p;
}

/// A range layer's value at (r, c). MRPT 2.5 may read a layer back with another shape than the
/// range image's; its row-major buffer is what was written (as mrptio::rangeLayer reads it).
unsigned layerAt(const mrpt::math::CMatrix_u16& m, int W, int r, int c) {
  const int cols = static_cast<int>(m.cols());
  const int i = r * W + c;
  return m(i / cols, i % cols);
}

std::size_t insertedPoints(const CObservation& o) {
  mrpt::maps::CSimplePointsMap map;
  map.insertionOptions.minDistBetweenLaserPoints = 0;
  map.insertObservation(o);
  return map.size();
}

struct Scan {
  std::size_t entry;
  CObservation::Ptr obs;
  CObservation::Ptr split;  ///< the "<label>_DYNAMIC" cloud after it, if any
};

std::vector<Scan> readScans(const std::string& path) {
  dynobj::mrptio::RawlogReader r(path);
  dynobj::mrptio::RawlogEntry e;
  std::vector<Scan> out;
  while (r.next(e))
    for (const auto& o : e.observations()) {
      if (isSplit(*o)) {
        if (out.empty()) throw Failure("split cloud '" + o->sensorLabel + "' before any scan");
        out.back().split = o;
      } else if (isLidar(*o)) {
        out.push_back({e.index, o, nullptr});
      }
    }
  return out;
}

void pairUp(const std::vector<Scan>& a, const std::vector<Scan>& b) {
  if (a.size() != b.size())
    throw Failure(std::to_string(a.size()) + " LiDAR scans in the first rawlog, " +
                  std::to_string(b.size()) + " in the second");
  for (std::size_t i = 0; i < a.size(); i++)
    if (a[i].obs->sensorLabel != b[i].obs->sensorLabel ||
        a[i].obs->GetRuntimeClass() != b[i].obs->GetRuntimeClass() ||
        a[i].obs->timestamp != b[i].obs->timestamp)
      throw Failure("scan " + std::to_string(i) + " (entry " + std::to_string(a[i].entry) +
                    "): label, class or timestamp differ");
}

/// A label file's sweeps, found by the scan's timestamp (`only`: for that sensor only).
struct Labels {
  std::optional<dynobj::io::LabelFile> file;
  std::string only;
  const dynobj::io::LabelSweep* sweepFor(const CObservation& o) const {
    if (!file || (!only.empty() && o.sensorLabel != only)) return nullptr;
    const std::int64_t t = dynobj::mrptio::toUnixNs(o.timestamp);
    for (const auto& s : file->sweeps)
      if (std::llabs(s.timestamp_ns - t) < 1000) return &s;
    return nullptr;
  }
};

int partition(const std::string& in, const std::string& out, const Labels& labels) {
  const auto a = readScans(in), b = readScans(out);
  pairUp(a, b);
  std::size_t total = 0, kept = 0, removed = 0, split_scans = 0, label_checked = 0;
  std::size_t unlabelled_untouched = 0, first_changed = SIZE_MAX, last_changed = 0;
  std::size_t label_counted = 0, label_points = 0;  ///< unorganized scans checked by count
  std::set<std::string> classes;
  for (std::size_t i = 0; i < a.size(); i++) {
    const std::string where = "scan " + std::to_string(i) + " (entry " +
                              std::to_string(a[i].entry) + ", '" + a[i].obs->sensorLabel + "')";
    classes.insert(a[i].obs->GetRuntimeClass()->className);
    std::vector<P3> pa = pointsOf(*a[i].obs), pb = pointsOf(*b[i].obs);
    std::sort(pa.begin(), pa.end());
    std::sort(pb.begin(), pb.end());
    std::vector<P3> gone;
    std::set_difference(pa.begin(), pa.end(), pb.begin(), pb.end(), std::back_inserter(gone));
    if (gone.size() + pb.size() != pa.size())
      throw Failure(where + ": the output holds points the input does not");
    if (insertedPoints(*b[i].obs) != pb.size())
      throw Failure(where + ": stock map insertion reads " +
                    std::to_string(insertedPoints(*b[i].obs)) + " points, the scan keeps " +
                    std::to_string(pb.size()));
    if (b[i].split) {
      std::vector<P3> ps = pointsOf(*b[i].split);
      std::sort(ps.begin(), ps.end());
      if (ps != gone)
        throw Failure(where + ": the split cloud holds " + std::to_string(ps.size()) +
                      " points, not the " + std::to_string(gone.size()) + " removed ones");
      split_scans++;
    }
    if (const auto* sweep = labels.sweepFor(*a[i].obs)) {
      const auto* sa = dynamic_cast<const CObservation3DRangeScan*>(a[i].obs.get());
      const auto* sb = dynamic_cast<const CObservation3DRangeScan*>(b[i].obs.get());
      if (!sa || !sb) {  // no pixel per point in the raw object: the counts must be equal
        if (gone.size() != sweep->pixels.size())
          throw Failure(where + ": removed " + std::to_string(gone.size()) + " points, the " +
                        "sweep labels " + std::to_string(sweep->pixels.size()) + " pixels");
        label_counted++;
        label_points += gone.size();
      } else {
        // The labelled pixels' points, from the input's pixel indices.
        std::vector<P3> on_labels;
        const std::set<std::uint32_t> px(sweep->pixels.begin(), sweep->pixels.end());
        const auto W = static_cast<std::uint32_t>(sa->rangeImage.cols());
        for (std::size_t k = 0; k < sa->points3D_x.size(); k++)
          if (px.count(sa->points3D_idxs_y[k] * W + sa->points3D_idxs_x[k]))
            on_labels.push_back({sa->points3D_x[k], sa->points3D_y[k], sa->points3D_z[k]});
        std::sort(on_labels.begin(), on_labels.end());
        if (on_labels != gone)
          throw Failure(where + ": removed " + std::to_string(gone.size()) +
                        " points, the labels' " + "pixels hold " +
                        std::to_string(on_labels.size()));
        const auto layer = sb->rangeImageOtherLayers.find("dynamic");
        for (int r = 0; r < sa->rangeImage.rows(); r++)
          for (int c = 0; c < sa->rangeImage.cols(); c++) {
            const bool lab =
                px.count(static_cast<std::uint32_t>(r) * W + static_cast<std::uint32_t>(c));
            const auto raw = sa->rangeImage(r, c);
            const auto now = sb->rangeImage(r, c);
            const auto moved = layer == sb->rangeImageOtherLayers.end()
                                   ? 0u
                                   : layerAt(layer->second, static_cast<int>(W), r, c);
            if (lab ? (now != 0 || moved != raw) : (now != raw || moved != 0))
              throw Failure(where + ": pixel (" + std::to_string(r) + ", " + std::to_string(c) +
                            ") range " + std::to_string(raw) + " -> " + std::to_string(now) +
                            ", layer " + std::to_string(moved) + (lab ? " (labelled)" : ""));
          }
        label_checked++;
      }
    } else if (labels.file && (labels.only.empty() || a[i].obs->sensorLabel == labels.only)) {
      if (!gone.empty())
        throw Failure(where + ": no sweep in the label file at its time, yet " +
                      std::to_string(gone.size()) + " points were removed");
      unlabelled_untouched++;
    }
    if (!gone.empty()) {
      first_changed = std::min(first_changed, a[i].entry);
      last_changed = std::max(last_changed, a[i].entry);
    }
    total += pa.size();
    kept += pb.size();
    removed += gone.size();
  }
  std::string cls;
  for (const auto& c : classes) cls += (cls.empty() ? "" : ", ") + c;
  std::printf(
      "partition: %zu scans (%s): %zu points = %zu kept + %zu removed; %zu split clouds "
      "hold exactly the removed points; %zu scans removed exactly their labelled pixels, "
      "%zu scans without a sweep untouched",
      a.size(), cls.c_str(), total, kept, removed, split_scans, label_checked,
      unlabelled_untouched);
  if (removed) std::printf("; points removed in entries %zu..%zu", first_changed, last_changed);
  if (label_counted)
    std::printf("; %zu unorganized scans removed as many points as their labelled pixels (%zu)",
                label_counted, label_points);
  std::printf("\n");
  return 0;
}

/// The points each scan lost from `in` to `out`, sorted.
std::vector<std::vector<P3>> removedPoints(const std::string& in, const std::string& out) {
  const auto a = readScans(in), b = readScans(out);
  pairUp(a, b);
  std::vector<std::vector<P3>> gone(a.size());
  for (std::size_t i = 0; i < a.size(); i++) {
    std::vector<P3> pa = pointsOf(*a[i].obs), pb = pointsOf(*b[i].obs);
    std::sort(pa.begin(), pa.end());
    std::sort(pb.begin(), pb.end());
    std::set_difference(pa.begin(), pa.end(), pb.begin(), pb.end(), std::back_inserter(gone[i]));
  }
  return gone;
}

/// Two recordings of the same sweeps (e.g. organized scans and unordered clouds of one simulation)
/// filtered alike: every scan lost exactly the same points in both.
int sameRemoval(const std::string& in_a, const std::string& out_a, const std::string& in_b,
                const std::string& out_b) {
  const auto ga = removedPoints(in_a, out_a), gb = removedPoints(in_b, out_b);
  if (ga.size() != gb.size())
    throw Failure(std::to_string(ga.size()) + " vs " + std::to_string(gb.size()) + " scans");
  std::size_t n = 0;
  for (std::size_t i = 0; i < ga.size(); i++) {
    if (ga[i] != gb[i])
      throw Failure("scan " + std::to_string(i) + ": " + std::to_string(ga[i].size()) + " vs " +
                    std::to_string(gb[i].size()) + " points removed, not the same points");
    n += ga[i].size();
  }
  std::printf("same removal: %zu scans, the same %zu points removed in both\n", ga.size(), n);
  return 0;
}

int marked(const std::string& in, const std::string& out, const Labels& labels) {
  const auto a = readScans(in), b = readScans(out);
  pairUp(a, b);
  std::size_t flagged = 0;
  for (std::size_t i = 0; i < a.size(); i++) {
    const std::string where = "scan " + std::to_string(i);
    const auto* sa = dynamic_cast<const CObservation3DRangeScan*>(a[i].obs.get());
    const auto* sb = dynamic_cast<const CObservation3DRangeScan*>(b[i].obs.get());
    if (!sa || !sb) throw Failure(where + ": mark is checked on range scans only");
    if (sa->points3D_x != sb->points3D_x || sa->points3D_y != sb->points3D_y ||
        sa->points3D_z != sb->points3D_z || sa->rangeImage != sb->rangeImage ||
        sb->rangeImageOtherLayers.count("dynamic"))
      throw Failure(where + ": mark changed the geometry");
    const auto* sweep = labels.sweepFor(*sa);
    if (!sweep) throw Failure(where + ": no sweep in the label file at its time");
    if (!sb->pixelLabels) throw Failure(where + ": no pixelLabels");
    const int bit = sb->pixelLabels->checkLabelNameExistence("dynamic");
    if (bit < 0) throw Failure(where + ": no label named 'dynamic'");
    const std::set<std::uint32_t> px(sweep->pixels.begin(), sweep->pixels.end());
    const int H = static_cast<int>(sa->rangeImage.rows()),
              W = static_cast<int>(sa->rangeImage.cols());
    for (int r = 0; r < H; r++)
      for (int c = 0; c < W; c++) {
        const bool lab = px.count(static_cast<std::uint32_t>(r * W + c)) > 0;
        if (sb->pixelLabels->checkLabel(r, c, static_cast<std::uint8_t>(bit)) != lab)
          throw Failure(where + ": pixel (" + std::to_string(r) + ", " + std::to_string(c) + ") " +
                        (lab ? "labelled but not marked" : "marked but not labelled"));
        flagged += lab;
      }
  }
  std::printf("marked: %zu scans, geometry unchanged, %zu pixels marked 'dynamic' = the labels\n",
              a.size(), flagged);
  return 0;
}

int same(const std::string& x, const std::string& y) {
  const auto a = readScans(x), b = readScans(y);
  pairUp(a, b);
  std::size_t points = 0;
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); i++) {
    const std::string where = "scan " + std::to_string(i);
    const auto* sa = dynamic_cast<const CObservation3DRangeScan*>(a[i].obs.get());
    const auto* sb = dynamic_cast<const CObservation3DRangeScan*>(b[i].obs.get());
    if (!sa || !sb) throw Failure(where + ": restore is checked on range scans only");
    if (sa->rangeImage != sb->rangeImage) throw Failure(where + ": range images differ");
    if (sb->rangeImageOtherLayers.count("dynamic"))
      throw Failure(where + ": a 'dynamic' layer is left");
    if (sa->points3D_x.size() != sb->points3D_x.size())
      throw Failure(where + ": " + std::to_string(sa->points3D_x.size()) + " vs " +
                    std::to_string(sb->points3D_x.size()) + " points");
    const auto W = static_cast<std::size_t>(sa->rangeImage.cols());
    std::map<std::size_t, P3> pa;
    for (std::size_t k = 0; k < sa->points3D_x.size(); k++)
      pa[sa->points3D_idxs_y[k] * W + sa->points3D_idxs_x[k]] = {
          sa->points3D_x[k], sa->points3D_y[k], sa->points3D_z[k]};
    for (std::size_t k = 0; k < sb->points3D_x.size(); k++) {
      const auto it = pa.find(sb->points3D_idxs_y[k] * W + sb->points3D_idxs_x[k]);
      if (it == pa.end()) throw Failure(where + ": a point on a pixel that had none");
      const double d =
          std::hypot(it->second[0] - sb->points3D_x[k], it->second[1] - sb->points3D_y[k],
                     it->second[2] - sb->points3D_z[k]);
      worst = std::max(worst, d);
      if (d > 1e-3)
        throw Failure(where + ": a point " + std::to_string(d) + " m from the original");
    }
    points += sb->points3D_x.size();
  }
  std::printf("same: %zu scans, %zu points, range images identical, largest point offset %.2g m\n",
              a.size(), points, worst);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  try {
    Labels labels;
    if (what == "partition" && argc >= 4 && argc <= 6) {
      if (argc >= 5) labels.file = dynobj::io::LabelFile::read(argv[4]);
      if (argc == 6) labels.only = argv[5];
      return partition(argv[2], argv[3], labels);
    }
    if (what == "marked" && argc == 5) {
      labels.file = dynobj::io::LabelFile::read(argv[4]);
      return marked(argv[2], argv[3], labels);
    }
    if (what == "same" && argc == 4) return same(argv[2], argv[3]);
    if (what == "same-removal" && argc == 6) return sameRemoval(argv[2], argv[3], argv[4], argv[5]);
    std::fprintf(stderr, "usage: rawlog_points partition|marked|same|same-removal <a> <b> [...]\n");
    return 2;
  } catch (const std::exception& e) {
    std::printf("rawlog_points %s: FAILED: %s\n", what.c_str(), e.what());
    return 1;
  }
}
