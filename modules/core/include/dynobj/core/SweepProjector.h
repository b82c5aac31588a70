// SPDX-License-Identifier: BSD-3-Clause
// The one conversion of a recording's unordered point-cloud sweeps (sensor frame, one cloud per
// sweep) into LidarFrames, shared by every reader of such sweeps: a folder of PCD / KITTI .bin
// files (mrptio::CloudFolderFrameSource: dynobj-detect, dynobj-eval, dynobj-import) and the Python
// module (numpy arrays). Per sweep: intensity on one scale for the whole recording (fractional
// remission 0-1 x 255, decided on the first sweep), rows recovered (RowRecovery: the first sweep
// whose rows come from a ring field or the firing order fixes the rows of the later ones).
#pragma once

#include <map>
#include <optional>

#include "dynobj/core/LidarFrame.h"
#include "dynobj/core/PointCloud.h"
#include "dynobj/core/RowRecovery.h"
#include "dynobj/core/SensorModel.h"
#include "dynobj/core/SphericalProjection.h"

namespace dynobj::core {

class SweepProjector {
 public:
  /// `sensor`: what is known of the sensor (RowRecovery's hint); none = recovered from the data.
  explicit SweepProjector(std::optional<SensorModel> sensor = std::nullopt);

  /// The next sweep of the recording into `frame` (timestamp left to the caller). Rescales
  /// `cloud.intensity` in place (the frame's points keep the cloud's indices). Throws
  /// std::invalid_argument when no row rule applies and there is no sensor model.
  ProjectionStats project(PointCloud& cloud, LidarFrame& frame);
  /// Starts a new recording (the scale and the rows learned are forgotten).
  void reset();

  /// The factor the intensities are stored with (255 for fractional ones, else 1); 0 before the
  /// first sweep.
  double intensityScale() const { return scale_; }
  /// The rule that gave the last sweep's rows.
  RowSource lastRowSource() const { return source_; }
  /// Lasers found in the last sweep (core::projectUnordered; 0 when the rows came from a table).
  int lastLasers() const { return lasers_; }

 private:
  std::optional<SensorModel> sensor_, hint_;
  double scale_ = 0;
  RowSource source_ = RowSource::NominalTable;
  int lasers_ = 0;
};

}  // namespace dynobj::core
