// SPDX-License-Identifier: BSD-3-Clause
// Where the labelling session's sweeps come from, one at a time and in any order: a rawlog
// (RawlogSweeps, through mrptio::RawlogIndex) or frames held in memory (tests, MemorySweeps).
#pragma once

#include <dynobj/core/LidarFrame.h>

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace dynobj::mrptio {
class RawlogIndex;
class ObservationConverter;
}  // namespace dynobj::mrptio

namespace dynobj::label {

class SweepSource {
 public:
  virtual ~SweepSource() = default;
  virtual std::size_t size() const = 0;
  virtual std::int64_t timestamp(std::size_t k) const = 0;
  /// Fills `frame` with sweep k and `pose` with the sensor's pose in the odometry frame when the
  /// input knows it (odometry x mount), else nullopt. Throws naming the input on bad data.
  virtual void load(std::size_t k, core::LidarFrame& frame,
                    std::optional<Eigen::Isometry3d>& pose) = 0;
  virtual std::string describe() const = 0;
};

/// Frames given in memory (tests; small inputs).
class MemorySweeps : public SweepSource {
 public:
  void add(core::LidarFrame frame, std::optional<Eigen::Isometry3d> pose = std::nullopt);
  std::size_t size() const override { return frames_.size(); }
  std::int64_t timestamp(std::size_t k) const override { return frames_.at(k).timestamp_ns; }
  void load(std::size_t k, core::LidarFrame& frame,
            std::optional<Eigen::Isometry3d>& pose) override;
  std::string describe() const override { return "frames in memory"; }

 private:
  std::vector<core::LidarFrame> frames_;
  std::vector<std::optional<Eigen::Isometry3d>> poses_;
};

/// The LiDAR sweeps of a rawlog, read on demand (memory: an index entry per sweep).
class RawlogSweeps : public SweepSource {
 public:
  /// Indexes the rawlog (one pass; `progress` gets entries and bytes read). Throws
  /// mrptio::RawlogError when it cannot be read to its end or holds no LiDAR sweep.
  RawlogSweeps(const std::string& rawlog, const mrptio::ObservationConverter& converter,
               const std::string& sensor_label,
               std::function<void(std::size_t, std::uint64_t)> progress = {});
  ~RawlogSweeps() override;
  std::size_t size() const override;
  std::int64_t timestamp(std::size_t k) const override;
  void load(std::size_t k, core::LidarFrame& frame,
            std::optional<Eigen::Isometry3d>& pose) override;
  std::string describe() const override;
  const std::string& sensorLabel() const;

 private:
  std::unique_ptr<mrptio::RawlogIndex> index_;
};

}  // namespace dynobj::label
