// SPDX-License-Identifier: BSD-3-Clause
// dynobj-import: a recording (folder of PCD / KITTI .bin sweeps, an Ouster pcap + metadata
// JSON, or a Velodyne pcap) -> a stock MRPT rawlog that every dynobj tool reads without a sensor
// option (dynobj::mrptio::importRecording; docs/usage.md, docs/formats.md "Importers").
#include <dynobj/core/SensorModel.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/RecordingImporter.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>

#include "../common/AppMain.h"

namespace {

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("dynobj-import: LiDAR recording -> MRPT rawlog (organized 3D scans)", ' ',
                     "0.1");
  TCLAP::ValueArg<std::string> in("i", "input",
                                  "Folder of .pcd/.bin sweeps, or an Ouster / Velodyne .pcap", true,
                                  "", "path", cmd);
  TCLAP::ValueArg<std::string> out("o", "output", "Output rawlog", true, "", "file.rawlog", cmd);
  TCLAP::SwitchArg overwrite("w", "overwrite", "Replace an existing output file", cmd);
  TCLAP::ValueArg<std::string> meta("", "meta", "Ouster sensor metadata JSON (for a pcap)", false,
                                    "", "file.json", cmd);
  TCLAP::ValueArg<std::string> model("", "model",
                                     "Velodyne pcap: the sensor model (default: from the "
                                     "packets): vlp-16, puck-hi-res, vlp-32c, hdl-32e, "
                                     "hdl-64e-s2, hdl-64e-s3, vls-128",
                                     false, "", "name", cmd);
  TCLAP::ValueArg<std::string> calib("", "calib",
                                     "Velodyne pcap: the unit's calibration (db.xml) instead of "
                                     "the manual's beam table; required for HDL-64E",
                                     false, "", "db.xml", cmd);
  TCLAP::ValueArg<std::string> dual("", "dual",
                                    "Velodyne dual-return pcap: the return kept per laser "
                                    "firing, strongest or last",
                                    false, "strongest", "strongest|last", cmd);
  TCLAP::ValueArg<int> port("", "port", "Velodyne pcap: UDP port of the data packets", false, 2368,
                            "port", cmd);
  TCLAP::ValueArg<std::string> times("", "times",
                                     "Folder: one time per sweep (KITTI times.txt or "
                                     "timestamps.txt, or ns); default: --rate",
                                     false, "", "file", cmd);
  TCLAP::ValueArg<double> rate("", "rate", "Folder without --times: sweeps per second", false, 10.0,
                               "Hz", cmd);
  TCLAP::ValueArg<std::string> poses("", "poses",
                                     "Poses (KITTI 3x4 rows or TUM), one per sweep: written as "
                                     "CObservationOdometry",
                                     false, "", "file", cmd);
  TCLAP::ValueArg<std::string> sensor("", "sensor",
                                      "Sensor preset INI: a hint for the rows/columns of "
                                      "point clouds (default: recovered from the data)",
                                      false, "", "file.ini", cmd);
  TCLAP::ValueArg<std::string> label("", "sensor-label", "Sensor label of the scans", false,
                                     "LIDAR", "label", cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);
  if (auto rc = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *rc;

  if (std::filesystem::exists(out.getValue()) && !overwrite.isSet())
    throw std::runtime_error("'" + out.getValue() + "' exists; use -w to replace it");
  dynobj::mrptio::ImportOptions o;
  o.input = in.getValue();
  o.meta = meta.getValue();
  o.velodyne_model = model.getValue();
  o.calib = calib.getValue();
  o.dual = dual.getValue();
  o.data_port = port.getValue();
  o.times = times.getValue();
  o.poses = poses.getValue();
  o.rate = rate.getValue();
  o.sensor_label = label.getValue();
  if (sensor.isSet()) o.sensor = dynobj::io::readSensorModel(sensor.getValue());
  o.sensor_file = sensor.getValue();
  const bool tty = !quiet.isSet() && isatty(STDERR_FILENO);
  const auto progress = [&](std::size_t done, std::size_t total) {
    if (!tty) return;
    if (total)
      std::fprintf(stderr, "\r  sweep %zu / %zu", done, total);
    else
      std::fprintf(stderr, "\r  sweep %zu", done);
  };
  const auto s = dynobj::mrptio::importRecording(o, out.getValue(), progress);
  if (tty) std::fprintf(stderr, "\n");
  std::printf(
      "dynobj-import: %zu sweeps of %dx%d from %s -> '%s'\n  rows from: %s; intensity: %s\n  "
      "%zu points -> %zu pixels (%zu share a pixel, %zu outside the field of view, %zu "
      "invalid); %zu odometry observations\n",
      s.sweeps, s.rows, s.cols, s.source.c_str(), out.getValue().c_str(), s.rows_from.c_str(),
      s.intensity.c_str(), s.points, s.pixels, s.hidden, s.outside_fov, s.invalid, s.odometry);
  if (s.second_pass)
    std::printf(
        "  %zu points scanned twice (sweeps of more than one revolution: each pixel keeps the "
        "first pass)\n",
        s.second_pass);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("dynobj-import", [&] { return run(argc, argv); });
}
