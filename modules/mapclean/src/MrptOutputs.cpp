// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mapclean/MrptOutputs.h"

#include <dynobj/io/AtomicFile.h>
#include <dynobj/mrptio/ObservationTagging.h>
#include <dynobj/mrptio/PoseConversion.h>
#include <dynobj/mrptio/RangeScanLayout.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPose3DPDFGaussian.h>
#include <mrpt/serialization/CArchive.h>

#include <cmath>
#include <stdexcept>

namespace dynobj::mapclean {

CleanedSimplemapWriter::CleanedSimplemapWriter(std::string path, double keyframe_distance,
                                               double keyframe_angle)
    : path_(std::move(path)), dist_(keyframe_distance), angle_(keyframe_angle) {}

void CleanedSimplemapWriter::add(const Scan& scan, const cv::Mat_<std::uint8_t>& dynamic_mask,
                                 const Eigen::Isometry3d& sensor_pose) {
  if (have_last_) {
    const Eigen::Isometry3d d = last_.inverse() * sensor_pose;
    const double angle = Eigen::AngleAxisd(d.linear()).angle();
    if (d.translation().norm() < dist_ && angle < angle_) return;
  }
  have_last_ = true;
  last_ = sensor_pose;
  auto obs = std::make_shared<mrpt::obs::CObservation3DRangeScan>();
  const auto* in = dynamic_cast<const mrpt::obs::CObservation3DRangeScan*>(scan.observation.get());
  if (in) {
    *obs = *in;
  } else {  // other LiDAR types (and PCD input): the organized layout of the frame
    mrptio::frameToRangeScan(scan.frame, *obs);
    obs->sensorLabel = scan.observation ? scan.observation->sensorLabel : std::string("LIDAR");
    obs->timestamp = mrptio::fromUnixNs(scan.frame.timestamp_ns);
    obs->sensorPose = mrptio::toCPose3D(scan.mount);
  }
  mrptio::dropDynamic(*obs, dynamic_mask);
  auto sf = std::make_shared<mrpt::obs::CSensoryFrame>();
  sf->insert(obs);
  const auto robot = mrptio::toCPose3D(sensor_pose * scan.mount.inverse());
  map_.insert(std::make_shared<mrpt::poses::CPose3DPDFGaussian>(robot), sf);
}

void CleanedSimplemapWriter::close() {
  const std::string partial = io::partialName(path_);
  if (!map_.saveToFile(partial)) {
    std::remove(partial.c_str());
    throw std::runtime_error(io::cannotWriteMessage(path_) + " (simplemap)");
  }
  io::commitPartial(path_);
}

std::size_t mergeSimplemaps(const std::vector<std::pair<std::string, Eigen::Isometry3d>>& parts,
                            const std::string& path) {
  mrpt::maps::CSimpleMap merged;
  for (const auto& [file, transform] : parts) {
    mrpt::maps::CSimpleMap part;
    bool ok = false;
    try {
      ok = part.loadFromFile(file);
    } catch (const std::exception&) {
      ok = false;
    }
    if (!ok) throw std::runtime_error("cannot read the simplemap '" + file + "'");
    part.changeCoordinatesOrigin(mrptio::toCPose3D(transform));
    for (std::size_t k = 0; k < part.size(); k++) merged.insert(part.getAsPair(k));
  }
  const std::string partial = io::partialName(path);
  if (!merged.saveToFile(partial)) {
    std::remove(partial.c_str());
    throw std::runtime_error(io::cannotWriteMessage(path) + " (simplemap)");
  }
  io::commitPartial(path);
  return merged.size();
}

namespace {

mrpt::maps::CPointsMapXYZI toPointsMap(const std::vector<MapPoint>& points) {
  mrpt::maps::CPointsMapXYZI map;
  map.resize(points.size());
  for (std::size_t i = 0; i < points.size(); i++) {
    map.setPointFast(i, points[i].x, points[i].y, points[i].z);
    map.setPointIntensity(i, points[i].intensity);
  }
  return map;
}

}  // namespace

void writePointsMapFile(const std::string& file, const std::vector<MapPoint>& points) {
  const mrpt::maps::CPointsMapXYZI map = toPointsMap(points);
  {
    mrpt::io::CFileGZOutputStream out;
    if (!out.open(io::partialName(file))) throw std::runtime_error(io::cannotWriteMessage(file));
    mrpt::serialization::archiveFrom(out) << map;
  }
  io::commitPartial(file);
}

void writePointsMapText(const std::string& txt, const std::vector<MapPoint>& points) {
  const mrpt::maps::CPointsMapXYZI map = toPointsMap(points);
  if (!map.saveXYZI_to_text_file(io::partialName(txt))) {
    std::remove(io::partialName(txt).c_str());
    throw std::runtime_error(io::cannotWriteMessage(txt));
  }
  io::commitPartial(txt);
}

}  // namespace dynobj::mapclean
