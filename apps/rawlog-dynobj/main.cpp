// SPDX-License-Identifier: BSD-3-Clause
// rawlog-dynobj: rawlog in -> rawlog out with the moving objects' points tagged (mark) or removed
// (drop, split) or put back (restore); a link in a rawlog-edit chain. Streams entry by entry,
// keeps the rawlog format, writes <out>.partial and renames it only when everything went well.
#include <dynobj/core/LabelFile.h>
#include <dynobj/mrpt/DynamicObjectFilter.h>
#include <dynobj/mrpt/RawlogReader.h>
#include <mrpt/config/CConfigFile.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/serialization/CArchive.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>

#include "../common/AppMain.h"

namespace {

namespace fs = std::filesystem;

int run(int argc, char** argv) {
  TCLAP::CmdLine cmd("rawlog-dynobj: tag or remove the points of moving objects in a rawlog", ' ',
                     "0.1");
  TCLAP::ValueArg<std::string> in("i", "input", "Input rawlog", true, "", "in.rawlog", cmd);
  TCLAP::ValueArg<std::string> out("o", "output", "Output rawlog", true, "", "out.rawlog", cmd);
  TCLAP::SwitchArg overwrite("w", "overwrite", "Replace an existing output file", cmd);
  TCLAP::SwitchArg quiet("q", "quiet", "No progress output", cmd);
  TCLAP::ValueArg<std::string> mode("", "mode", "mark | drop | split | restore (default: drop)",
                                    false, "drop", "mode", cmd);
  TCLAP::ValueArg<std::string> config("c", "config", "Detector parameters (INI)", false, "",
                                      "file.ini", cmd);
  TCLAP::ValueArg<std::string> section("", "section", "Prefix of the INI sections (e.g. dynobj_)",
                                       false, "", "prefix", cmd);
  TCLAP::ValueArg<std::string> sensor(
      "", "sensor", "Sensor preset INI (point clouds, rotating scans)", false, "", "file.ini", cmd);
  TCLAP::ValueArg<std::string> label("", "sensor-label", "Only the LiDAR with this label", false,
                                     "", "label", cmd);
  TCLAP::ValueArg<std::string> labels_out(
      "", "labels-out", "Also write the detections (label file v1)", false, "", "file.labels", cmd);
  TCLAP::ValueArg<std::string> tracks_out(
      "", "tracks-out", "Also write the tracked objects, one CSV row per frame and track", false,
      "", "file.csv", cmd);
  TCLAP::ValueArg<std::size_t> from("", "from", "First entry to filter (earlier ones are copied)",
                                    false, 0, "N", cmd);
  TCLAP::ValueArg<std::size_t> to("", "to", "Last entry to filter (later ones are copied)", false,
                                  std::numeric_limits<std::size_t>::max(), "N", cmd);
  if (const auto stop = dynobj::apps::parseCommandLine(cmd, argc, argv)) return *stop;

  dynobj::mrpt::DynamicObjectFilter::Options opts;
  try {
    opts.mode = dynobj::mrpt::parseFilterMode(mode.getValue());
  } catch (const std::invalid_argument& e) {
    std::cerr << "rawlog-dynobj: error: --mode: " << e.what() << "\n";
    return 2;
  }
  opts.sensor_label = label.getValue();
  if (sensor.isSet()) opts.sensor = dynobj::core::SensorModel::fromFile(sensor.getValue());
  if (config.isSet()) {
    if (!fs::exists(config.getValue()))
      throw std::runtime_error("config file '" + config.getValue() + "' does not exist");
    ::mrpt::config::CConfigFile cfg(config.getValue());
    opts.detector.load(cfg, section.getValue());
  }
  // Never touch the input; never replace an output unless asked.
  std::error_code ec;
  if (fs::exists(out.getValue()) && fs::equivalent(in.getValue(), out.getValue(), ec))
    throw std::runtime_error("the output '" + out.getValue() + "' is the input file");
  if (fs::exists(out.getValue()) && !overwrite.isSet())
    throw std::runtime_error("output '" + out.getValue() + "' exists (use -w to replace it)");

  dynobj::mrpt::RawlogReader reader(in.getValue());
  const std::string partial = out.getValue() + ".partial";
  ::mrpt::io::CFileGZOutputStream file;
  if (!file.open(partial)) throw std::runtime_error("cannot write '" + partial + "'");
  struct Cleanup {  // an error anywhere leaves no partial file behind
    std::string path;
    bool armed = true;
    ~Cleanup() {
      if (armed) std::remove(path.c_str());
    }
  } cleanup{partial};
  auto arch = ::mrpt::serialization::archiveFrom(file);

  std::ofstream tracks;
  const std::string tracks_partial = tracks_out.getValue() + ".partial";
  if (tracks_out.isSet()) {
    tracks.open(tracks_partial);
    if (!tracks) throw std::runtime_error("cannot write '" + tracks_partial + "'");
    tracks << "timestamp_ns,sensor_label,id,dynamic,age,points,x,y,z,vx,vy,min_x,min_y,min_z,max_x,"
              "max_y,max_z\n";
  }
  struct TracksCleanup {
    std::string path;
    bool armed;
    ~TracksCleanup() {
      if (armed) std::remove(path.c_str());
    }
  } tracks_cleanup{tracks_partial, tracks_out.isSet()};

  dynobj::mrpt::DynamicObjectFilter filter(opts);
  std::unique_ptr<dynobj::core::LabelFileWriter> labels;
  std::string labels_sensor;
  const bool tty = !quiet.isSet() && isatty(STDERR_FILENO);
  const auto t0 = std::chrono::steady_clock::now();
  dynobj::mrpt::RawlogEntry e;
  std::vector<::mrpt::obs::CObservation::Ptr> extra;
  auto onResult = [&](const ::mrpt::obs::CObservation& obs,
                      const dynobj::core::DetectionResult* r) {
    if (r && tracks_out.isSet())
      for (const auto& o : r->objects)
        tracks << r->timestamp_ns << ',' << obs.sensorLabel << ',' << o.id << ','
               << (o.dynamic ? 1 : 0) << ',' << o.age << ',' << o.points << ',' << o.centroid.x()
               << ',' << o.centroid.y() << ',' << o.centroid.z() << ',' << o.velocity.x() << ','
               << o.velocity.y() << ',' << o.box_min.x() << ',' << o.box_min.y() << ','
               << o.box_min.z() << ',' << o.box_max.x() << ',' << o.box_max.y() << ','
               << o.box_max.z() << '\n';
    if (!r || !labels_out.isSet()) return;
    if (!labels) {
      labels_sensor = obs.sensorLabel;
      labels = std::make_unique<dynobj::core::LabelFileWriter>(labels_out.getValue(),
                                                               r->dynamic.rows, r->dynamic.cols);
    } else if (obs.sensorLabel != labels_sensor) {
      throw std::runtime_error("--labels-out: the rawlog has several LiDARs ('" + labels_sensor +
                               "', '" + obs.sensorLabel + "'); choose one with --sensor-label");
    }
    labels->write(r->timestamp_ns, dynobj::core::pixelsOfMask(r->dynamic));
  };
  while (reader.next(e)) {
    const bool in_range = e.index >= from.getValue() && e.index <= to.getValue();
    if (!in_range) {  // outside --from/--to: copied unchanged
      if (e.isPair()) {
        if (e.actions) arch << *e.actions;
        arch << *e.sensory_frame;
      } else {
        arch << *e.observation;
      }
      continue;
    }
    if (e.isPair()) {
      std::vector<::mrpt::obs::CObservation::Ptr> sf_extra;
      for (auto& o : *e.sensory_frame) onResult(*o, filter.filter(o, &sf_extra));
      for (auto& o : sf_extra) e.sensory_frame->insert(o);
      if (e.actions) arch << *e.actions;
      arch << *e.sensory_frame;
    } else {
      extra.clear();
      onResult(*e.observation, filter.filter(e.observation, &extra));
      arch << *e.observation;
      for (auto& o : extra) arch << *o;
    }
    if (tty && e.index % 10 == 0) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      std::fprintf(stderr, "\r[rawlog-dynobj] entry %zu, %zu LiDAR frames, %.1f frames/s   ",
                   e.index + 1, filter.summary().lidar,
                   s > 0 ? static_cast<double>(filter.summary().lidar) / s : 0.0);
    }
  }
  file.close();
  if (labels) labels->close();
  if (tracks_out.isSet()) {
    tracks.close();
    if (!tracks) throw std::runtime_error("error writing '" + tracks_partial + "'");
    fs::rename(tracks_partial, tracks_out.getValue());
    tracks_cleanup.armed = false;
  }
  fs::rename(partial, out.getValue());
  cleanup.armed = false;
  if (tty) std::fprintf(stderr, "\n");
  const auto& sm = filter.summary();
  std::printf(
      "rawlog-dynobj: %zu entries, %zu observations; %zu LiDAR frames (%s): %zu points, %zu "
      "dynamic "
      "(%.2f%%); %zu passed through; %.2f ms/frame\n",
      reader.entriesRead(), sm.observations, sm.lidar, dynobj::mrpt::toString(opts.mode), sm.points,
      sm.dynamic_points,
      sm.points ? 100.0 * static_cast<double>(sm.dynamic_points) / static_cast<double>(sm.points)
                : 0.0,
      sm.passed_through, sm.lidar ? sm.detector_ms / static_cast<double>(sm.lidar) : 0.0);
  for (const auto& [msg, n] : sm.warnings) std::printf("  warning (%zux): %s\n", n, msg.c_str());
  if (sm.lidar == 0 && sm.passed_through == 0)
    std::printf("  note: no LiDAR observation%s was found; the output is a copy of the input\n",
                label.isSet() ? (" with label '" + label.getValue() + "'").c_str() : "");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return dynobj::apps::runApp("rawlog-dynobj", [&] { return run(argc, argv); });
}
