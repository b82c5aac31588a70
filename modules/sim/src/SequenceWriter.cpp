// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/SequenceWriter.h"

#include <dynobj/mrptio/RangeScanLayout.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <mrpt/maps/CPointsMapXYZI.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationPointCloud.h>
#include <mrpt/poses/CPose3D.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <stdexcept>

namespace dynobj::sim {
namespace {

::mrpt::poses::CPose2D planar(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d R = T.linear();
  return {T.translation().x(), T.translation().y(), std::atan2(R(1, 0), R(0, 0))};
}

/// The sweep as an unordered cloud, KITTI-style: laser by laser (in the preset's laser-id order),
/// each laser one revolution in firing order (the head turns clockwise from behind: column W-1
/// first); remission = intensity / `full_scale`, clipped to [0, 1].
::mrpt::obs::CObservationPointCloud pointCloud(const Scenario& s, const core::LidarFrame& f) {
  ::mrpt::obs::CObservationPointCloud obs;
  auto pc = std::make_shared<::mrpt::maps::CPointsMapXYZI>();
  pc->reserve(f.validCount());
  const double full_scale =
      s.intensity_model == IntensityModel::Velodyne ? 100.0 : s.intensity_gain;
  for (const int r : s.sensor.laserToRow())  // laser ids in order, each its image row
    for (int c = f.cols() - 1; c >= 0; c--) {
      if (!f.isValid(r, c)) continue;
      const cv::Vec3f& p = f.xyz(r, c);
      pc->insertPointFast(p[0], p[1], p[2]);
      pc->setPointIntensity(
          pc->size() - 1, static_cast<float>(std::clamp(f.intensity(r, c) / full_scale, 0.0, 1.0)));
    }
  obs.pointcloud = pc;
  return obs;
}

}  // namespace

SequenceWriter::SequenceWriter(const std::string& out_dir, const Scenario& scenario,
                               int compression)
    : s_(scenario), base_(out_dir + "/" + scenario.name), odo_rng_(scenario.seed ^ 0x5EEDu) {
  if (compression < 0 || compression > mrptio::RawlogWriter::kMaxLevel)
    throw std::invalid_argument("rawlog compression must be 0..3, got " +
                                std::to_string(compression));
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (!std::filesystem::is_directory(out_dir))
    throw std::runtime_error("cannot create output directory '" + out_dir + "'");
  rawlog_ = std::make_unique<mrptio::RawlogWriter>(rawlogPath(), compression,
                                                   mrptio::RawlogWriter::hardwareThreads());
  labels_ = std::make_unique<io::LabelFileWriter>(labelsPath(), s_.sensor.rows, s_.sensor.cols);
  instances_ =
      std::make_unique<io::LabelFileWriter>(instancesPath(), s_.sensor.rows, s_.sensor.cols, true);
  tum_ =
      std::make_unique<io::TumWriter>(tumPath(), "sensor '" + s_.sensor_label + "' in the world");
  objects_ = std::make_unique<io::AtomicFile>(objectsPath());
  objects_->stream() << "sweep,timestamp_ns,id,class,x,y,z,vx,vy,speed,moving,points\n";
}

SequenceWriter::~SequenceWriter() = default;  // every writer removes its own partial file

void SequenceWriter::write(const SimulatedSweep& sw) {
  const auto stamp = dynobj::mrptio::fromUnixNs(sw.timestamp_ns);
  if (s_.odometry) {  // noisy wheel/leg odometry: true increments plus per-sweep noise
    const ::mrpt::poses::CPose2D truth = planar(sw.robot_pose);
    if (have_last_) {
      ::mrpt::poses::CPose2D inc = truth - last_true_;
      std::normal_distribution<double> g(0.0, 1.0);
      inc.x(inc.x() + s_.odometry_sigma_xy * g(odo_rng_));
      inc.y(inc.y() + s_.odometry_sigma_xy * g(odo_rng_));
      inc.phi(inc.phi() + s_.odometry_sigma_yaw * g(odo_rng_));
      odometry_ = odometry_ + inc;
    } else {
      odometry_ = truth;
    }
    last_true_ = truth;
    have_last_ = true;
    ::mrpt::obs::CObservationOdometry odo;
    odo.sensorLabel = "ODOMETRY";
    odo.timestamp = stamp;
    odo.odometry = odometry_;
    rawlog_->write(odo);
  }
  const ::mrpt::poses::CPose3D mount(s_.mount.x(), s_.mount.y(), s_.mount.z(), 0, 0, 0);
  if (s_.output == OutputFormat::PointCloud) {
    ::mrpt::obs::CObservationPointCloud cloud = pointCloud(s_, sw.frame);
    cloud.sensorLabel = s_.sensor_label;
    cloud.timestamp = stamp;
    cloud.sensorPose = mount;
    rawlog_->write(cloud);
  } else {
    ::mrpt::obs::CObservation3DRangeScan scan;
    dynobj::mrptio::frameToRangeScan(sw.frame, scan);
    scan.sensorLabel = s_.sensor_label;
    scan.timestamp = stamp;
    scan.sensorPose = mount;
    rawlog_->write(scan);
  }

  labels_->write(sw.timestamp_ns, io::pixelsOfMask(sw.dynamic));
  std::vector<std::uint32_t> pixels;  // every pixel that hit an actor, moving or not
  std::vector<std::int32_t> ids;
  for (int i = 0; i < sw.actor.rows * sw.actor.cols; i++)
    if (sw.actor(i / sw.actor.cols, i % sw.actor.cols) >= 0) {
      pixels.push_back(static_cast<std::uint32_t>(i));
      ids.push_back(sw.actor(i / sw.actor.cols, i % sw.actor.cols));
    }
  instances_->write(sw.timestamp_ns, pixels, ids);

  tum_->write(sw.timestamp_ns, sw.sensor_pose);
  for (const ActorState& a : sw.actors)
    objects_->stream() << sw.index << "," << sw.timestamp_ns << "," << a.id << ","
                       << toString(a.cls) << "," << std::setprecision(3) << a.position.x() << ","
                       << a.position.y() << "," << a.position.z() << "," << a.velocity.x() << ","
                       << a.velocity.y() << "," << a.velocity.norm() << "," << (a.moving ? 1 : 0)
                       << "," << a.points << "\n";
}

void SequenceWriter::close() {
  rawlog_->commit();
  labels_->close();
  instances_->close();
  tum_->close();
  objects_->commit();
}

}  // namespace dynobj::sim
