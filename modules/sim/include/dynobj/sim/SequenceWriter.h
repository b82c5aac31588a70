// SPDX-License-Identifier: BSD-3-Clause
// Writes a simulated sequence into one folder (docs/formats.md, docs/simulator.md):
//   <name>.rawlog            observation-only rawlog: [CObservationOdometry] +
//   CObservation3DRangeScan <name>.gt.labels         dynamic-label file v1 (pixels hit by a moving
//   actor) <name>.gt.tum            sensor poses, TUM format (timestamp tx ty tz qx qy qz qw,
//   seconds) <name>.gt.objects.csv    per sweep and actor: id, class, position, velocity, moving,
//   points
// Every file is written as <file>.partial and renamed only by close(): a file with the final name
// is always complete.
#pragma once

#include <dynobj/io/AtomicFile.h>
#include <dynobj/io/LabelFile.h>
#include <dynobj/io/PoseFile.h>
#include <dynobj/mrptio/RawlogWriter.h>
#include <mrpt/poses/CPose2D.h>

#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "dynobj/sim/LidarSimulator.h"

namespace dynobj::sim {

class SequenceWriter {
 public:
  /// Creates `out_dir` if needed. Throws std::runtime_error naming a file it cannot create.
  /// `compression` = gzip level of the rawlog, 0 (a plain rawlog: fastest, largest) to 3
  /// (mrptio::RawlogWriter); readers do not care.
  SequenceWriter(const std::string& out_dir, const Scenario& scenario, int compression = 1);
  ~SequenceWriter();
  SequenceWriter(const SequenceWriter&) = delete;
  SequenceWriter& operator=(const SequenceWriter&) = delete;

  void write(const SimulatedSweep& sweep);
  /// Flushes and renames every file into place.
  void close();

  /// Final paths.
  std::string rawlogPath() const { return base_ + ".rawlog"; }
  std::string labelsPath() const { return base_ + ".gt.labels"; }
  std::string instancesPath() const { return base_ + ".gt.instances"; }
  std::string tumPath() const { return base_ + ".gt.tum"; }
  std::string objectsPath() const { return base_ + ".gt.objects.csv"; }

 private:
  const Scenario& s_;
  std::string base_;
  std::unique_ptr<mrptio::RawlogWriter> rawlog_;
  std::unique_ptr<io::LabelFileWriter> labels_, instances_;
  std::unique_ptr<io::TumWriter> tum_;
  std::unique_ptr<io::AtomicFile> objects_;
  std::mt19937 odo_rng_;
  ::mrpt::poses::CPose2D odometry_;
  ::mrpt::poses::CPose2D last_true_;
  bool have_last_ = false;
};

}  // namespace dynobj::sim
