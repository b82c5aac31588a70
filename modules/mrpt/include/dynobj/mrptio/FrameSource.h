// SPDX-License-Identifier: BSD-3-Clause
// Where SequenceRunner's frames come from: one LiDAR sweep at a time (memory stays flat), as a
// core::LidarFrame plus what the input says about it. Sources: RawlogFrameSource (MRPT rawlogs),
// mapclean's PCD folders, eval's simulator in process; a new input format = one more subclass.
#pragma once

#include <dynobj/core/LidarFrame.h>
#include <dynobj/core/PointCloud.h>
#include <dynobj/core/SphericalProjection.h>
#include <mrpt/obs/CObservation.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

namespace dynobj::mrptio {

struct Frame {
  std::size_t index = 0;     ///< LiDAR frame number in the source (0-based)
  std::size_t entry = 0;     ///< rawlog entry (rawlog sources; else = index)
  std::string where;         ///< for messages: "'x.rawlog' entry 12", "pcd/000012.pcd"
  std::string sensor_label;  ///< the detector's key (DetectorBank)
  core::LidarFrame frame;    ///< sensor frame; frame.timestamp_ns is the sweep's time
  core::ProjectionStats stats;
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  ///< sensor pose on the robot
  std::optional<Eigen::Isometry3d> odometry;   ///< robot pose of the latest odometry (rawlog)
  std::optional<Eigen::Isometry3d> viewpoint;  ///< sensor pose given by the input (PCD VIEWPOINT)
  mrpt::obs::CObservation::Ptr observation;    ///< the rawlog's observation (null otherwise)
  /// The input points in the sensor frame, in the file's order (point-cloud file sources: every
  /// point of the file, frame.point_pixel maps each to its pixel); empty for other sources.
  core::PointCloud points;
};

class FrameSource {
 public:
  virtual ~FrameSource() = default;
  /// The next frame into `f` (its buffers are reused); false at the end. Throws naming the file
  /// and entry on bad input.
  virtual bool next(Frame& f) = 0;
  /// Starts again from the first frame (multi-pass users such as map cleaning).
  virtual void rewind() = 0;
  virtual std::string describe() const = 0;
  /// After a pass that gave no frame: what the source holds instead (e.g. " with label 'X';
  /// labels seen: ..."), appended to "no LiDAR observation in <describe()>". Default: nothing.
  virtual std::string noFramesDetail() const { return {}; }
  /// Passes over the next frame, giving only its time (a sweep's, as next() would); false at the
  /// end. Default: next() into a scratch frame; sources that can do it without converting the
  /// sweep (rawlogs) override it.
  virtual bool nextTime(std::int64_t& timestamp_ns);
  /// From the next call on, next() and nextTime() pass over the frames before `timestamp_ns`
  /// (cheaply where a source can; the frames keep their numbers). Default: nothing is passed over
  /// (callers drop such frames themselves: TimeWindowSource).
  virtual void skipBefore(std::int64_t /*timestamp_ns*/) {}
  /// The share of the input read so far (0-1, for progress and time estimates); negative when
  /// the source cannot tell.
  virtual double progress() const { return -1; }
};

inline bool FrameSource::nextTime(std::int64_t& timestamp_ns) {
  Frame f;
  if (!next(f)) return false;
  timestamp_ns = f.frame.timestamp_ns;
  return true;
}

}  // namespace dynobj::mrptio
