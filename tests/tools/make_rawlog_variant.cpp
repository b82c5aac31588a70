// SPDX-License-Identifier: BSD-3-Clause
// Test tool: rewrites an observation-format rawlog of organized CObservation3DRangeScan sweeps (the
// simulator's) into the other shapes users' rawlogs come in, so the command-line tests can run
// rawlog-dynobj on them:
//   make_rawlog_variant velodyne <in> <out> <sensor.ini>
//       every LiDAR scan as a CObservationVelodyneScan holding the same points in point_cloud
//       (laser_id from the preset's laser order, intensity clipped to 0-255, no calibration: the
//       filter needs --sensor), other observations unchanged;
//   make_rawlog_variant two-lidars <in> <out>
//       after each LiDAR scan the same scan again under the label "<label>2" (a second sensor);
//   make_rawlog_variant sensory-frames <in> <out>
//       the old format: one (CActionCollection, CSensoryFrame) pair per LiDAR scan; the action is
//       the odometry increment since the previous scan (CActionRobotMovement2D), the scan (and
//       nothing else) in the sensory frame.
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/mrptio/RawlogWriter.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationOdometry.h>
#include <mrpt/obs/CObservationVelodyneScan.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

namespace {

using namespace mrpt::obs;

CObservationVelodyneScan::Ptr toVelodyne(const CObservation3DRangeScan& s,
                                         const std::vector<int>& row_to_laser) {
  auto v = std::make_shared<CObservationVelodyneScan>();
  v->sensorLabel = s.sensorLabel;
  v->timestamp = s.timestamp;
  v->sensorPose = s.sensorPose;
  v->minRange = 0.1;
  v->maxRange = s.maxRange;
  const auto inten = s.rangeImageOtherLayers.find("intensity");
  auto& pc = v->point_cloud;
  for (std::size_t i = 0; i < s.points3D_x.size(); i++) {
    const int row = s.points3D_idxs_y[i], col = s.points3D_idxs_x[i];
    double in = 0;
    if (inten != s.rangeImageOtherLayers.end())
      in = inten->second(row, col);
    else if (s.hasIntensityImage)
      in = s.intensityImage.asCvMatRef().at<std::uint8_t>(row, col);
    pc.x.push_back(s.points3D_x[i]);
    pc.y.push_back(s.points3D_y[i]);
    pc.z.push_back(s.points3D_z[i]);
    pc.intensity.push_back(static_cast<std::uint8_t>(std::clamp(std::lround(in), 0L, 255L)));
    pc.timestamp.push_back(s.timestamp);
    pc.azimuth.push_back(static_cast<float>(std::atan2(s.points3D_y[i], s.points3D_x[i])));
    pc.laser_id.push_back(
        static_cast<std::int16_t>(row_to_laser.at(static_cast<std::size_t>(row))));
  }
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string what = argc > 1 ? argv[1] : "";
  if (!((what == "velodyne" && argc == 5) ||
        ((what == "two-lidars" || what == "sensory-frames") && argc == 4))) {
    std::fprintf(stderr,
                 "usage: make_rawlog_variant velodyne|two-lidars|sensory-frames <in> <out> "
                 "[sensor.ini]\n");
    return 2;
  }
  try {
    std::vector<int> row_to_laser;
    if (what == "velodyne") {
      const auto model = dynobj::io::readSensorModel(argv[4]);
      const auto l2r = model.laserToRow();
      row_to_laser.assign(l2r.size(), 0);
      for (std::size_t l = 0; l < l2r.size(); l++)
        row_to_laser.at(static_cast<std::size_t>(l2r[l])) = static_cast<int>(l);
    }
    dynobj::mrptio::RawlogReader in(argv[2]);
    dynobj::mrptio::RawlogWriter out(argv[3]);
    dynobj::mrptio::RawlogEntry e;
    std::optional<mrpt::poses::CPose2D> last_odo, odo;
    std::size_t scans = 0;
    while (in.next(e)) {
      if (e.isPair()) throw std::runtime_error("the input must be in the observation format");
      const auto* scan = dynamic_cast<const CObservation3DRangeScan*>(e.observation.get());
      if (what == "sensory-frames") {
        if (const auto* o = dynamic_cast<const CObservationOdometry*>(e.observation.get()))
          odo = o->odometry;
        if (!scan) continue;  // only the scans go into the output, each with its odometry step
        CActionCollection acts;
        CActionRobotMovement2D mv;
        CActionRobotMovement2D::TMotionModelOptions opts;
        const mrpt::poses::CPose2D now = odo.value_or(mrpt::poses::CPose2D());
        mv.computeFromOdometry(last_odo ? now - *last_odo : mrpt::poses::CPose2D(), opts);
        mv.timestamp = e.observation->timestamp;
        last_odo = now;
        acts.insert(mv);
        CSensoryFrame sf;
        sf.insert(e.observation);
        out.write(acts);
        out.write(sf);
      } else if (scan && what == "velodyne") {
        out.write(*toVelodyne(*scan, row_to_laser));
      } else {
        out.write(*e.observation);
        if (scan && what == "two-lidars") {
          auto copy = std::make_shared<CObservation3DRangeScan>(*scan);
          copy->sensorLabel = scan->sensorLabel + "2";
          out.write(*copy);
        }
      }
      scans += scan != nullptr;
    }
    out.commit();
    std::printf("make_rawlog_variant %s: %zu LiDAR scans\n", what.c_str(), scans);
    return 0;
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "make_rawlog_variant: error: %s\n", ex.what());
    return 1;
  }
}
