// SPDX-License-Identifier: BSD-3-Clause
// dynobj-frames: converts the LiDAR observations of a rawlog into LiDAR frames and writes their
// range and intensity images as PNG, with one line of statistics per frame.
#include <dynobj/io/FrameImages.h>
#include <dynobj/io/Png.h>
#include <dynobj/mrptio/RawlogFrameSource.h>
#include <dynobj/mrptio/SequenceRunner.h>

#include <cstdio>
#include <iostream>
#include <optional>

#include "../common/AppOptions.h"

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-frames: write the range/intensity images of a rawlog's LiDAR scans",
                     ' ', "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "Input rawlog", true, "", "file.rawlog", cmd);
  const dynobj::apps::OutputArg out(cmd, "Output directory (created if missing)", false, "dir",
                                    "out-dir", ".");
  dynobj::apps::SensorArgs sensor(cmd);
  TCLAP::ValueArg<std::size_t> from("", "from", "First entry index", false, 0, "N", cmd);
  TCLAP::ValueArg<std::size_t> to("", "to", "Last entry index (inclusive)", false,
                                  std::numeric_limits<std::size_t>::max(), "N", cmd);
  TCLAP::ValueArg<int> row_scale("", "row-scale", "Repeat each row K times in the PNGs", false, 1,
                                 "K", cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "Print only the summary", cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;
  if (row_scale.getValue() < 1 || row_scale.getValue() > 64) {
    std::cerr << "dynobj-frames: error: --row-scale must be in [1, 64]\n";
    return 2;
  }

  const std::string dir = out.getValue();
  dynobj::apps::OutputFolder folder(dir);  // removed again if no image is written

  dynobj::mrptio::RawlogFrameSource stream(in.getValue(), sensor.converter(),
                                           {sensor.label(), from.getValue(), to.getValue()});
  dynobj::mrptio::SequenceOptions so;
  so.detect = false;  // frames only
  so.require_frames = false;
  const std::size_t frames = dynobj::mrptio::SequenceRunner(stream, so).run([&](const auto& r) {
    const dynobj::mrptio::Frame& item = r.frame;
    char name[64];
    std::snprintf(name, sizeof(name), "_%06zu_", item.entry);
    const std::string prefix = dir + "/" + item.sensor_label + name;
    dynobj::io::writeFramePngs(item.frame, prefix, row_scale.getValue());
    if (!quiet.isSet())
      std::cout << "entry " << item.entry << " '" << item.sensor_label << "' "
                << item.observation->GetRuntimeClass()->className << ": " << item.frame.rows()
                << "x" << item.frame.cols() << ", " << item.stats.toString()
                << (item.frame.has_intensity ? "" : ", no intensity (range image used)") << "\n"
                << "  -> " << prefix << "range.png, " << prefix << "intensity.png\n";
  });
  if (frames == 0) {
    std::string seen;
    for (const auto& [l, cls] : stream.labelsSeen()) seen += " '" + l + "' (" + cls + ")";
    throw std::runtime_error(
        "no LiDAR observation" + (sensor.labelSet() ? " with label '" + sensor.label() + "'" : "") +
        " in '" + in.getValue() + "'; labels seen:" + (seen.empty() ? " none" : seen));
  }
  folder.keep();
  std::cout << "dynobj-frames: " << frames << " frame(s) from " << stream.entriesRead()
            << " entries written to " << dir << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-frames", [&] { return run(argc, argv); });
}
