// SPDX-License-Identifier: BSD-3-Clause
// Test tool: what a simplemap holds, read with MRPT's own reader: keyframes, their organized
// range scans, kept points, dropped points (ranges in the layer "dynamic") and pixels marked
// "dynamic"; with a ground-truth label file (v1, matched by timestamp) also how many kept points
// and dropped or marked pixels lie on moving actors.
//   simplemap_info <file.simplemap> [gt.labels]
#include <dynobj/io/LabelFile.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <mrpt/io/CFileGZInputStream.h>
#include <mrpt/maps/CSimpleMap.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>

int main(int argc, char** argv) {
  if (argc != 2 && argc != 3) {
    std::fprintf(stderr, "usage: simplemap_info <file.simplemap> [gt.labels]\n");
    return 2;
  }
  try {
    mrpt::maps::CSimpleMap sm;
    mrpt::io::CFileGZInputStream f(argv[1]);
    mrpt::serialization::archiveFrom(f) >> sm;
    std::optional<dynobj::io::LabelFile> gt;
    if (argc == 3) gt = dynobj::io::LabelFile::read(argv[2]);
    std::size_t scans = 0, kept = 0, dropped = 0, marked = 0, scans_with_gt = 0;
    std::size_t kept_on_gt = 0, dropped_on_gt = 0, marked_on_gt = 0;
    for (std::size_t k = 0; k < sm.size(); k++) {
      mrpt::poses::CPose3DPDF::Ptr pose;
      mrpt::obs::CSensoryFrame::Ptr sf;
      sm.get(k, pose, sf);
      for (const auto& o : *sf) {
        const auto* s = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(o.get());
        if (!s) continue;
        scans++;
        const auto W = static_cast<std::uint32_t>(s->rangeImage.cols());
        std::set<std::uint32_t> truth;
        if (gt) {
          const std::int64_t t = dynobj::mrptio::toUnixNs(s->timestamp);
          for (const auto& sw : gt->sweeps)
            if (std::llabs(sw.timestamp_ns - t) < 1000) {
              truth.insert(sw.pixels.begin(), sw.pixels.end());
              scans_with_gt++;
            }
        }
        kept += s->points3D_x.size();
        for (std::size_t i = 0; i < s->points3D_x.size(); i++)
          kept_on_gt += truth.count(s->points3D_idxs_y[i] * W + s->points3D_idxs_x[i]);
        const auto layer = s->rangeImageOtherLayers.find("dynamic");
        const int bit = s->pixelLabels ? s->pixelLabels->checkLabelNameExistence("dynamic") : -1;
        for (int r = 0; r < s->rangeImage.rows(); r++)
          for (int c = 0; c < s->rangeImage.cols(); c++) {
            const bool on_gt =
                truth.count(static_cast<std::uint32_t>(r) * W + static_cast<std::uint32_t>(c)) > 0;
            // MRPT 2.5 may read a layer back in another shape: index its row-major buffer.
            const int i = r * static_cast<int>(W) + c;
            const auto& m = layer == s->rangeImageOtherLayers.end() ? s->rangeImage : layer->second;
            const int mc = static_cast<int>(m.cols());
            if (layer != s->rangeImageOtherLayers.end() && m(i / mc, i % mc) != 0) {
              dropped++;
              dropped_on_gt += on_gt;
            }
            if (bit >= 0 && s->pixelLabels->checkLabel(r, c, static_cast<std::uint8_t>(bit))) {
              marked++;
              marked_on_gt += on_gt;
            }
          }
      }
    }
    std::printf(
        "simplemap: %zu keyframes, %zu range scans, %zu points kept, %zu dropped, %zu "
        "pixels marked dynamic\n",
        sm.size(), scans, kept, dropped, marked);
    if (gt)
      std::printf(
          "ground truth (%zu scans matched): kept on moving actors %zu, dropped on moving "
          "actors %zu of %zu, marked on moving actors %zu of %zu\n",
          scans_with_gt, kept_on_gt, dropped_on_gt, dropped, marked_on_gt, marked);
    return 0;
  } catch (const std::exception& e) {
    std::printf("simplemap_info: error: %s\n", e.what());
    return 1;
  }
}
