// SPDX-License-Identifier: BSD-3-Clause
// Ground truth per input point, for real recordings labelled by people (docs/accuracy.md, "Real
// recordings"): every point of a sweep is *moving*, *static* or *unknown* (left out of the
// score), and a moving point names its object. Two sources:
//  - BoxTruth: 3-D boxes with track ids (KITTI tracking label_02 + calib, or the generic
//    box-track file of io/BoxTrackFile.h). Boxes say nothing about motion: a track moves where
//    its world trajectory (the boxes placed by the sensor poses) covers at least `moving_speed`
//    over `speed_window`; below `static_speed` it stands still; in between, or where it was seen
//    too briefly to tell, its points are unknown. Points near a moving box (`band`, including the
//    ground under it) and points outside the annotated field of view are unknown.
//  - SemanticKittiTruth: SemanticKITTI `.label` files (moving classes 251-259, unlabeled 0 =
//    unknown, the rest static).
// Neither is ever given to the detector: they score its output.
#pragma once

#include <dynobj/core/PointCloud.h>
#include <dynobj/io/BoxTrackFile.h>
#include <dynobj/io/KittiTracking.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dynobj::eval {

enum class PointLabel : std::uint8_t { Static = 0, Moving = 1, Unknown = 2 };

/// One sweep's truth, one entry per input point (in the input's order).
struct SweepTruth {
  std::vector<PointLabel> label;
  std::vector<std::int32_t> object;  ///< the moving object of a moving point, else -1
};

/// Where per-point truth comes from. Sources that judge motion from trajectories need the sensor
/// poses of every sweep first (setSensorPoses).
class PointTruthSource {
 public:
  virtual ~PointTruthSource() = default;
  virtual bool needsPoses() const { return false; }
  /// Sensor poses in a fixed world frame and times of the recording's sweeps, in order.
  virtual void setSensorPoses(const std::vector<Eigen::Isometry3d>& /*poses*/,
                              const std::vector<std::int64_t>& /*stamps_ns*/) {}
  /// The truth of sweep `k` for its input points (sensor frame). Throws EvaluationError when the
  /// source does not fit (a label count that differs from the point count, ...).
  virtual SweepTruth truthOf(std::size_t k, const core::PointCloud& points) const = 0;
  /// The class of a moving object ("Car", "Pedestrian", "person", ...).
  virtual std::string className(int object) const = 0;
  virtual std::string describe() const = 0;
};

/// One human box in the sensor frame of its sweep.
struct TruthBox {
  int track = 0;
  std::string cls;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  ///< box centre and axes -> sensor
  Eigen::Vector3d size{0, 0, 0};  ///< [m] along the box's x (length), y (width), z (height)
};

struct BoxTruthParams {
  double moving_speed = 0.5;  ///< [m/s] a track at least this fast over speed_window moves
  double static_speed = 0.2;  ///< [m/s] below this it stands still; in between: unknown
  double speed_window = 3.0;  ///< [s] centred on the sweep (box jitter averages out)
  double min_span = 0.5;      ///< [s] a shorter trajectory (a track seen once) is unknown
  double band = 0.2;          ///< [m] around a moving box, and its lowest part: unknown

  /// Throws std::invalid_argument naming the bad key.
  void validate() const;
};

/// What a track did over the recording (for reports): its speed per sweep where judged.
struct TrackMotion {
  int track = 0;
  std::string cls;
  std::vector<std::size_t> sweeps;
  std::vector<double> speed;  ///< [m/s] per sweep, NaN where not judged
  std::vector<PointLabel> state;
};

class BoxTruth final : public PointTruthSource {
 public:
  /// `boxes[k]`: the boxes of sweep k. `annotated`: whether a sensor-frame point lies where
  /// people annotated (empty: everywhere).
  BoxTruth(std::vector<std::vector<TruthBox>> boxes, BoxTruthParams params,
           std::function<bool(const Eigen::Vector3d&)> annotated, std::string description);

  /// KITTI tracking labels and calibration; annotated = inside the left colour image
  /// (`image_width` x `image_height` px through P2, in front of the camera). DontCare rows are
  /// left out.
  static std::unique_ptr<BoxTruth> fromKitti(const std::string& label_file,
                                             const std::string& calib_file, const BoxTruthParams& p,
                                             int image_width = 1242, int image_height = 375);
  /// The generic box-track file; annotated everywhere.
  static std::unique_ptr<BoxTruth> fromBoxTrackFile(const std::string& path,
                                                    const BoxTruthParams& p);

  bool needsPoses() const override { return true; }
  void setSensorPoses(const std::vector<Eigen::Isometry3d>& poses,
                      const std::vector<std::int64_t>& stamps_ns) override;
  SweepTruth truthOf(std::size_t k, const core::PointCloud& points) const override;
  std::string className(int object) const override;
  std::string describe() const override { return description_; }

  /// Each track's judged motion (after setSensorPoses).
  const std::vector<TrackMotion>& tracks() const { return tracks_; }
  std::size_t sweeps() const { return boxes_.size(); }

 private:
  std::vector<std::vector<TruthBox>> boxes_;
  BoxTruthParams p_;
  std::function<bool(const Eigen::Vector3d&)> annotated_;
  std::string description_;
  std::vector<std::vector<PointLabel>> state_;  ///< per sweep, per box: Static/Moving/Unknown
  std::vector<TrackMotion> tracks_;
  std::map<int, std::string> classes_;
};

class SemanticKittiTruth final : public PointTruthSource {
 public:
  /// `dir`: the .label files, one per sweep, in natural name order (as the sweeps).
  explicit SemanticKittiTruth(const std::string& dir);
  SweepTruth truthOf(std::size_t k, const core::PointCloud& points) const override;
  std::string className(int object) const override;
  std::string describe() const override { return "SemanticKITTI labels '" + dir_ + "'"; }
  std::size_t sweeps() const { return files_.size(); }

 private:
  std::string dir_;
  std::vector<std::string> files_;
  mutable std::map<int, std::string> classes_;
};

/// The truth a user names: a folder of SemanticKITTI .label files, a box-track file (*.csv), or a
/// KITTI tracking label file (then `calib` is required). Throws EvaluationError / io::FormatError.
std::unique_ptr<PointTruthSource> openPointTruth(const std::string& path, const std::string& calib,
                                                 const BoxTruthParams& p = {});

/// The truth of `sweep` as SemanticKITTI labels (0 unknown, 9 static, moving: the object's moving
/// class and its id in the upper 16 bits).
std::vector<std::uint32_t> toSemanticKitti(const SweepTruth& t, const PointTruthSource& source);

}  // namespace dynobj::eval
