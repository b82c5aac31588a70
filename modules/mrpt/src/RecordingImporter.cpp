// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RecordingImporter.h"

#include <dynobj/io/FormatError.h>
#include <dynobj/io/OusterPcapReader.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/io/VelodynePcapReader.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/VelodyneCalibration.h>
#include <mrpt/poses/CPose2D.h>
#include <mrpt/serialization/CArchive.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <vector>

#include "dynobj/mrptio/CloudFolderFrameSource.h"
#include "dynobj/mrptio/RangeScanLayout.h"
#include "dynobj/mrptio/RawlogWriter.h"
#include "dynobj/mrptio/TimeConversion.h"

namespace dynobj::mrptio {
namespace {

namespace fs = std::filesystem;

class SweepWriter {
 public:
  SweepWriter(const ImportOptions& o, const std::string& output, std::size_t sweeps)
      : o_(o), out_(output, 1, RawlogWriter::hardwareThreads()) {  // compressed alongside
    if (!o.poses.empty()) {
      poses_ = io::readPoseFile(o.poses);
      if (sweeps && poses_.size() != sweeps)
        throw std::runtime_error("'" + o.poses + "' has " + std::to_string(poses_.size()) +
                                 " poses but the recording has " + std::to_string(sweeps) +
                                 " sweeps");
    }
  }

  void write(const core::LidarFrame& frame, const core::ProjectionStats& st, ImportSummary& s) {
    const auto stamp = fromUnixNs(frame.timestamp_ns);
    if (!poses_.empty()) {
      if (s.sweeps >= poses_.size())
        throw std::runtime_error("'" + o_.poses + "' has no pose for sweep " +
                                 std::to_string(s.sweeps));
      const Eigen::Isometry3d& p = poses_[s.sweeps].pose;
      mrpt::obs::CObservationOdometry odo;
      odo.sensorLabel = "ODOMETRY";
      odo.timestamp = stamp;
      odo.odometry = mrpt::poses::CPose2D(p.translation().x(), p.translation().y(),
                                          std::atan2(p.linear()(1, 0), p.linear()(0, 0)));
      out_.write(odo);
      s.odometry++;
    }
    mrpt::obs::CObservation3DRangeScan scan;
    frameToRangeScan(frame, scan);
    scan.sensorLabel = o_.sensor_label;
    scan.timestamp = stamp;
    out_.write(scan);
    s.sweeps++;
    s.points += st.input_points;
    s.pixels += st.pixels_set;
    s.hidden += st.hidden;
    s.second_pass += st.second_pass;
    s.outside_fov += st.outside_fov;
    s.invalid += st.invalid;
    s.rows = frame.rows();
    s.cols = frame.cols();
  }
  void commit() { out_.commit(); }

 private:
  const ImportOptions& o_;
  RawlogWriter out_;
  std::vector<io::TimedPose> poses_;
};

/// Points of the sweeps so far against the --sensor preset's field of view.
struct PresetFit {
  std::size_t valid = 0, outside = 0;
};

/// Throws unless the --sensor preset fits sweep `file` (and the sweeps before it, `fit`): no more
/// lasers in the data than rows in the preset, and at most o.max_outside_fov of the valid points
/// outside its field of view.
void checkPresetFits(const ImportOptions& o, const std::string& file, int lasers,
                     const core::ProjectionStats& st, PresetFit& fit) {
  const core::SensorModel& m = *o.sensor;
  const std::string preset = "the sensor preset '" + o.sensor_file + "' (" + m.model + ", " +
                             std::to_string(m.rows) + " rows)";
  if (lasers > m.rows)
    throw std::runtime_error(preset + " does not fit the data: '" + file + "' holds " +
                             std::to_string(lasers) + " lasers; give the preset of the sensor " +
                             "that recorded it, or no --sensor (rows from the data)");
  fit.valid += st.input_points - st.invalid;
  fit.outside += st.outside_fov;
  const double share = fit.valid ? static_cast<double>(fit.outside) / fit.valid : 0.0;
  if (share > o.max_outside_fov) {
    char pct[32];
    std::snprintf(pct, sizeof(pct), "%.1f %%", 100.0 * share);
    throw std::runtime_error(
        preset + " does not fit the data: " + std::to_string(fit.outside) + " of the " +
        std::to_string(fit.valid) + " valid points (" + pct + ") of the sweeps up to '" + file +
        "' fall outside its field of " +
        "view; give the preset of the sensor that recorded it, or no --sensor");
  }
}

ImportSummary importFolder(const ImportOptions& o, const std::string& output,
                           const ImportProgress& progress) {
  CloudFolderFrameSource source(o.input, {o.times, o.rate, o.sensor, o.sensor_label});
  ImportSummary s;
  s.source = source.describe();
  SweepWriter writer(o, output, source.folder().size());
  PresetFit fit;
  Frame f;
  while (source.next(f)) {
    if (o.sensor)
      checkPresetFits(o, source.folder().path(f.index), source.lastLasers(), f.stats, fit);
    writer.write(f.frame, f.stats, s);
    if (progress) progress(f.index + 1, source.folder().size());
  }
  s.rows_from = describeRowSources(source.rowSources());
  s.intensity = source.intensityDescription();
  writer.commit();
  return s;
}

ImportSummary importOuster(const ImportOptions& o, const std::string& output,
                           const ImportProgress& progress) {
  const io::OusterMetadata meta = io::OusterMetadata::load(o.meta);
  io::OusterPcapReader reader(o.input, meta);
  const core::SensorModel model = meta.sensorModel();
  const core::SphericalProjection organizer(model);
  ImportSummary s;
  s.source = "Ouster pcap '" + o.input + "' (" + meta.prod_line + ", " + meta.profile + ")";
  s.rows_from = "metadata beam table";
  SweepWriter writer(o, output, 0);
  io::OusterScan scan;
  core::LidarFrame frame;
  while (reader.next(scan)) {
    const core::ProjectionStats st = organizer.organize(scan.cloud, frame);
    frame.timestamp_ns = scan.timestamp_ns;
    s.intensity = scan.intensity_field;
    writer.write(frame, st, s);
    if (progress) progress(s.sweeps, 0);
  }
  if (s.sweeps == 0)
    throw io::FormatError(o.input + ": no complete frame (" +
                          std::to_string(reader.stats().partial_frames_skipped) +
                          " partial frames skipped)");
  writer.commit();
  return s;
}

/// A Velodyne unit calibration (db.xml) through MRPT's reader: elevation and rotCorrection per
/// laser [deg]. MRPT 2.5.8's YAML reader cannot read a file (loadFromYAMLText treats the text as
/// a path), so only XML is accepted.
void loadVelodyneCalibration(const std::string& path, io::VelodyneOptions& v) {
  if (!fs::exists(path)) throw std::runtime_error("'" + path + "' does not exist");
  const std::string ext = fs::path(path).extension().string();
  if (ext == ".yaml" || ext == ".yml")
    throw io::FormatError(path +
                          ": give the unit's db.xml (MRPT 2.5 cannot read YAML "
                          "calibrations)");
  mrpt::obs::VelodyneCalibration cal;
  if (!cal.loadFromXMLFile(path) || cal.laser_corrections.empty())
    throw io::FormatError(path + ": not a Velodyne calibration (db.xml) MRPT can read");
  for (const auto& lc : cal.laser_corrections) {
    v.elevation_deg.push_back(lc.verticalCorrection);
    v.azimuth_correction_deg.push_back(lc.azimuthCorrection);
  }
  v.calibration_source = path;
}

ImportSummary importVelodyne(const ImportOptions& o, const std::string& output,
                             const ImportProgress& progress) {
  io::VelodynePcapReader::Options v;
  if (!o.velodyne_model.empty()) {
    v.decoder.model = io::VelodyneSensor::fromName(o.velodyne_model);
    if (!v.decoder.model)
      throw std::invalid_argument("unknown Velodyne model '" + o.velodyne_model +
                                  "' (known: " + io::VelodyneSensor::modelNames() + ")");
  }
  if (o.dual == "strongest" || o.dual == "last")
    v.decoder.dual = o.dual == "last" ? io::DualReturn::Last : io::DualReturn::Strongest;
  else
    throw std::invalid_argument("--dual must be 'strongest' or 'last', not '" + o.dual + "'");
  if (!o.calib.empty()) loadVelodyneCalibration(o.calib, v.decoder);
  v.data_port = o.data_port;
  io::VelodynePcapReader reader(o.input, v);
  ImportSummary s;
  std::optional<core::SphericalProjection> organizer;
  std::optional<SweepWriter> writer;
  io::VelodyneScan scan;
  core::LidarFrame frame;
  try {
    while (reader.next(scan)) {
      if (!organizer) {
        organizer.emplace(reader.decoder().sensorModel());
        writer.emplace(o, output, 0);
      }
      const core::ProjectionStats st = organizer->organize(scan.cloud, frame);
      frame.timestamp_ns = scan.timestamp_ns;
      writer->write(frame, st, s);
      if (progress) progress(s.sweeps, 0);
    }
  } catch (const io::FormatError& e) {
    const std::string what = e.what();
    if (what.find("no Velodyne data packets") != std::string::npos)
      throw io::FormatError(what + " (an Ouster capture needs its metadata JSON: --meta)");
    throw;
  }
  const io::VelodynePcapReader::Stats& st = reader.stats();
  if (s.sweeps == 0)
    throw io::FormatError(o.input + ": no complete sweep (" +
                          std::to_string(st.partial_frames_skipped) +
                          " partial sweeps of less than 180 deg skipped)");
  const io::VelodyneDecoder& d = reader.decoder();
  char freq[32];
  std::snprintf(freq, sizeof(freq), "%.2f Hz", d.frequencyHz());
  s.source = "Velodyne pcap '" + o.input + "' (" + d.sensor().name + ", model " + d.modelSource() +
             ", " + freq + "; " + std::to_string(st.data_packets) + " data + " +
             std::to_string(st.position_packets) + " position packets, " +
             std::to_string(st.partial_frames_skipped) + " partial sweeps skipped" +
             (d.dualReturn() ? ", dual return: kept the " + o.dual + " (" +
                                   std::to_string(st.second_returns_dropped) + " dropped)"
                             : std::string()) +
             ")";
  s.rows_from = o.calib.empty() ? "the " + d.sensor().name + " beam table of its user manual"
                                : "calibration '" + o.calib + "'";
  s.intensity = "Velodyne intensity 0-255";
  writer->commit();
  return s;
}

ImportSummary importPcap(const ImportOptions& o, const std::string& output,
                         const ImportProgress& progress) {
  return o.meta.empty() ? importVelodyne(o, output, progress) : importOuster(o, output, progress);
}

}  // namespace

ImportSummary importRecording(const ImportOptions& o, const std::string& output,
                              const ImportProgress& progress) {
  if (!(o.rate > 0)) throw std::invalid_argument("the sweep rate must be > 0 Hz");
  if (fs::is_directory(o.input)) return importFolder(o, output, progress);
  if (!fs::exists(o.input)) throw std::runtime_error("'" + o.input + "' does not exist");
  const std::string ext = fs::path(o.input).extension().string();
  if (ext == ".pcap" || ext == ".pcapng") return importPcap(o, output, progress);
  throw std::runtime_error("'" + o.input +
                           "' is neither a folder of .pcd/.bin sweeps nor a .pcap capture");
}

}  // namespace dynobj::mrptio
