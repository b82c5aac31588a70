// SPDX-License-Identifier: BSD-3-Clause
// dynobj-frames: converts the LiDAR observations of a rawlog into LiDAR frames and writes their
// range and intensity images as PNG, with one line of statistics per frame.
#include <dynobj/core/FrameImages.h>
#include <dynobj/io/Png.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/RawlogFrameSource.h>

#include <cstdio>
#include <iostream>
#include <optional>

#include "../common/AppMain.h"

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-frames: write the range/intensity images of a rawlog's LiDAR scans",
                     ' ', "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "Input rawlog", true, "", "file.rawlog", cmd);
  const dynobj::apps::OutputArg out(cmd, "Output directory (created if missing)", false, "dir",
                                    "out-dir", ".");
  TCLAP::ValueArg<std::string> sensor("", "sensor",
                                      "Sensor preset INI (share/dynobj/sensors/*.ini); needed for "
                                      "point clouds and rotating scans",
                                      false, "", "file.ini", cmd);
  TCLAP::ValueArg<std::string> label("", "sensor-label", "Only this sensor label", false, "",
                                     "label", cmd);
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

  std::optional<dynobj::core::SensorModel> model;
  if (sensor.isSet()) model = dynobj::io::readSensorModel(sensor.getValue());
  const std::string dir = out.getValue();
  dynobj::apps::ensureDirectory(dir);

  dynobj::mrptio::RawlogFrameSource stream(in.getValue(),
                                           dynobj::mrptio::ObservationConverter(model),
                                           {label.getValue(), from.getValue(), to.getValue()});
  dynobj::mrptio::Frame item;
  std::size_t frames = 0;
  while (stream.next(item)) {
    char name[64];
    std::snprintf(name, sizeof(name), "_%06zu_", item.entry);
    const std::string prefix = dir + "/" + item.observation->sensorLabel + name;
    dynobj::io::writeFramePngs(item.frame, prefix, row_scale.getValue());
    if (!quiet.isSet())
      std::cout << "entry " << item.entry << " '" << item.observation->sensorLabel << "' "
                << item.observation->GetRuntimeClass()->className << ": " << item.frame.rows()
                << "x" << item.frame.cols() << ", " << item.stats.toString()
                << (item.frame.has_intensity ? "" : ", no intensity (range image used)") << "\n"
                << "  -> " << prefix << "range.png, " << prefix << "intensity.png\n";
    frames++;
  }
  if (frames == 0) {
    std::string seen;
    for (const auto& [l, cls] : stream.labelsSeen()) seen += " '" + l + "' (" + cls + ")";
    throw std::runtime_error(
        "no LiDAR observation" + (label.isSet() ? " with label '" + label.getValue() + "'" : "") +
        " in '" + in.getValue() + "'; labels seen:" + (seen.empty() ? " none" : seen));
  }
  std::cout << "dynobj-frames: " << frames << " frame(s) from " << stream.entriesRead()
            << " entries written to " << dir << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-frames", [&] { return run(argc, argv); });
}
