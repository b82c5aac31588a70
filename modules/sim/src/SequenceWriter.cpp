// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/sim/SequenceWriter.h"

#include <dynobj/mrptio/RangeScanLayout.h>
#include <dynobj/mrptio/TimeConversion.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/poses/CPose3D.h>

#include <cstdio>
#include <filesystem>
#include <iomanip>

namespace dynobj::sim {
namespace {

::mrpt::poses::CPose2D planar(const Eigen::Isometry3d& T) {
  const Eigen::Matrix3d R = T.linear();
  return {T.translation().x(), T.translation().y(), std::atan2(R(1, 0), R(0, 0))};
}

}  // namespace

SequenceWriter::SequenceWriter(const std::string& out_dir, const Scenario& scenario)
    : s_(scenario), base_(out_dir + "/" + scenario.name), odo_rng_(scenario.seed ^ 0x5EEDu) {
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (!std::filesystem::is_directory(out_dir))
    throw std::runtime_error("cannot create output directory '" + out_dir + "'");
  rawlog_ = std::make_unique<mrptio::RawlogWriter>(rawlogPath());
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
  ::mrpt::obs::CObservation3DRangeScan scan;
  dynobj::mrptio::frameToRangeScan(sw.frame, scan);
  scan.sensorLabel = s_.sensor_label;
  scan.timestamp = stamp;
  scan.sensorPose = ::mrpt::poses::CPose3D(s_.mount.x(), s_.mount.y(), s_.mount.z(), 0, 0, 0);
  rawlog_->write(scan);

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
