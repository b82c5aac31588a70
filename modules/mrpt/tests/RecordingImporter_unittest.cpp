// SPDX-License-Identifier: BSD-3-Clause
// dynobj-import's Velodyne path against MRPT: the beam tables against MRPT 2.5's built-in
// defaults, the decoded points of the real HDL-32E capture against MRPT's own decoder
// (CObservationVelodyneScan::generatePointCloud), the rawlog importRecording writes, and the
// calibration errors. The real-capture tests skip where ../shared/realdata/velodyne is absent.
#include <dynobj/io/FormatError.h>
#include <dynobj/io/PcapReader.h>
#include <dynobj/io/VelodynePcapReader.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <dynobj/mrptio/RecordingImporter.h>
#include <gtest/gtest.h>
#include <mrpt/obs/CObservation3DRangeScan.h>
#include <mrpt/obs/CObservationVelodyneScan.h>
#include <mrpt/obs/VelodyneCalibration.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

using namespace dynobj;

namespace {

const std::string kDir = DYNOBJ_SOURCE_DIR "/../shared/realdata/velodyne/";
const std::string kHdl32 = kDir + "monterey-hdl32-first-100-packets.pcap";

#define SKIP_WITHOUT_REAL_DATA()            \
  if (!std::filesystem::is_directory(kDir)) \
  GTEST_SKIP() << "../shared/realdata/velodyne not found: real-capture tests skipped"

std::string tempPath(const std::string& name) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  return ::testing::TempDir() + "importer_" + test->name() + "_" + name;
}

TEST(RecordingImporterVelodyne, BeamTablesMatchMrptDefaults) {
  for (const auto& [model, mrpt_name] : {std::pair{io::VelodyneModel::VLP16, "VLP16"},
                                         std::pair{io::VelodyneModel::HDL32E, "HDL32"}}) {
    const auto& cal = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration(mrpt_name);
    const io::VelodyneSensor ours = io::VelodyneSensor::of(model);
    ASSERT_EQ(cal.laser_corrections.size(), ours.elevation_deg.size()) << mrpt_name;
    for (std::size_t l = 0; l < ours.elevation_deg.size(); l++) {
      EXPECT_NEAR(cal.laser_corrections[l].verticalCorrection, ours.elevation_deg[l],
                  1e-6);  // MRPT: 7 digits
      EXPECT_DOUBLE_EQ(cal.laser_corrections[l].azimuthCorrection, ours.azimuth_correction_deg[l]);
    }
  }
}

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"  // MRPT's wrapper base has no virtual dtor
struct MrptPoints : public mrpt::obs::CObservationVelodyneScan::PointCloudStorageWrapper {
  std::vector<std::vector<std::array<float, 3>>> per_laser = decltype(per_laser)(32);
  void add_point(float x, float y, float z, std::uint8_t, const mrpt::system::TTimeStamp&, float,
                 std::uint16_t laser_id) override {
    per_laser.at(laser_id).push_back({x, y, z});
  }
};
#pragma GCC diagnostic pop

TEST(RecordingImporterVelodyne, Hdl32PointsAgreeWithMrptsDecoder) {
  SKIP_WITHOUT_REAL_DATA();
  // MRPT: every data packet in one observation, its default HDL-32E calibration, no filters.
  mrpt::obs::CObservationVelodyneScan obs;
  obs.calibration = mrpt::obs::VelodyneCalibration::LoadDefaultCalibration("HDL32");
  obs.minRange = 0.0;
  obs.maxRange = 1000.0;
  io::PcapReader pcap(kHdl32);
  io::PcapReader::Datagram d;
  while (pcap.next(d)) {
    if (d.dst_port != 2368) continue;
    ASSERT_EQ(d.payload.size(), sizeof(mrpt::obs::CObservationVelodyneScan::TVelodyneRawPacket));
    obs.scan_packets.emplace_back();
    std::memcpy(&obs.scan_packets.back(), d.payload.data(), d.payload.size());
  }
  mrpt::obs::CObservationVelodyneScan::TGeneratePointCloudParameters params;
  params.minDistance = 0.0f;
  MrptPoints mrpt_points;
  obs.generatePointCloud(mrpt_points, params);

  // Ours: the kept sweeps, per laser in firing order.
  std::vector<std::vector<std::array<float, 3>>> ours(32);
  io::VelodynePcapReader reader(kHdl32, {});
  io::VelodyneScan scan;
  while (reader.next(scan))
    for (std::size_t i = 0; i < scan.cloud.size(); i++)
      ours[scan.cloud.ring[i]].push_back({scan.cloud.x[i], scan.cloud.y[i], scan.cloud.z[i]});

  // MRPT keeps fewer points (471,975 of the 872,800 returns here, below) and ends later (our
  // last, partial sweep is dropped): per laser, each MRPT point within our sweeps must be the next
  // of ours with the same range and height, its azimuth off by at most the firing delay MRPT does
  // not interpolate (laser l fires 1.152 l us into a 46.08 us firing of 0.195 deg).
  std::size_t compared = 0;
  double max_da = 0;
  for (std::size_t l = 0; l < 32; l++) {
    const auto& m = mrpt_points.per_laser[l];
    const auto& o = ours[l];
    const double tolerance = (0.195 * 1.152 * static_cast<double>(l) / 46.08 + 0.02) * M_PI / 180;
    std::size_t j = 0;
    for (std::size_t k = 0; k < m.size(); k++) {
      const auto& q = m[k];
      const double rq = std::hypot(q[0], q[1], q[2]);
      while (j < o.size()) {
        const auto& p = o[j];
        const double da = std::remainder(std::atan2(p[1], p[0]) - std::atan2(q[1], q[0]), 2 * M_PI);
        if (std::abs(std::hypot(p[0], p[1], p[2]) - rq) < 1e-3 && std::abs(p[2] - q[2]) < 1e-3 &&
            std::abs(da) <= tolerance) {
          max_da = std::max(max_da, std::abs(da));
          break;
        }
        j++;
      }
      if (j == o.size()) break;  // past our last sweep
      compared++;
      j++;
    }
    // Our points run out only within MRPT's last partial sweep: at most one turn is left over.
    EXPECT_GT(compared, 0u);
  }
  std::printf(
      "HDL-32E: %zu of MRPT's %zu points matched in order; azimuth difference <= %.3f deg\n",
      compared,
      [&] {
        std::size_t n = 0;
        for (const auto& v : mrpt_points.per_laser) n += v.size();
        return n;
      }(),
      max_da * 180 / M_PI);
  // MRPT 2.5.8 decodes 16 of the 32 channels of each block (as for the VLP-16): no points of
  // lasers 16-31 (elevations -20 .. +10.67 deg), which we decode.
  for (std::size_t l = 16; l < 32; l++) {
    EXPECT_TRUE(mrpt_points.per_laser[l].empty()) << "laser " << l;
    EXPECT_FALSE(ours[l].empty()) << "laser " << l;
  }
  std::size_t mrpt_total = 0;
  for (const auto& v : mrpt_points.per_laser) mrpt_total += v.size();
  // Every MRPT point but those of the last partial sweep (< 1 turn: < 32 x 1844 returns).
  EXPECT_GE(compared + 32 * 1844, mrpt_total);
}

TEST(RecordingImporterVelodyne, Hdl32CaptureBecomesOrganizedScans) {
  SKIP_WITHOUT_REAL_DATA();
  mrptio::ImportOptions o;
  o.input = kHdl32;
  const std::string out = tempPath("monterey.rawlog");
  const mrptio::ImportSummary s = mrptio::importRecording(o, out);
  EXPECT_EQ(s.rows, 32);
  EXPECT_NEAR(s.cols, 1850, 15);
  EXPECT_GE(s.sweeps, 16u);
  EXPECT_NE(s.source.find("HDL-32E, model product id 0x21"), std::string::npos) << s.source;
  EXPECT_EQ(s.points, s.pixels + s.hidden + s.outside_fov + s.invalid);
  EXPECT_EQ(s.outside_fov, 0u);
  // Two firings sharing a column are rare: one column per firing.
  EXPECT_LT(static_cast<double>(s.hidden), 0.01 * static_cast<double>(s.points));
  mrptio::RawlogReader reader(out);
  mrptio::RawlogEntry e;
  std::size_t scans = 0, points = 0;
  while (reader.next(e))
    for (const auto& obs : e.observations()) {
      const auto scan = std::dynamic_pointer_cast<mrpt::obs::CObservation3DRangeScan>(obs);
      ASSERT_TRUE(scan);
      EXPECT_EQ(scan->rangeImage.rows(), 32);
      EXPECT_EQ(scan->rangeImage.cols(), s.cols);
      points += scan->points3D_x.size();
      scans++;
    }
  EXPECT_EQ(scans, s.sweeps);
  EXPECT_EQ(points, s.pixels);
  std::filesystem::remove(out);
}

TEST(RecordingImporterVelodyne, CalibrationErrors) {
  mrptio::ImportOptions o;
  o.input = tempPath("any.pcap");
  std::ofstream(o.input) << "x";
  o.calib = tempPath("calib.yaml");
  std::ofstream(o.calib) << "lasers: []\n";
  const std::string out = tempPath("out.rawlog");
  try {
    mrptio::importRecording(o, out);
    ADD_FAILURE() << "no error";
  } catch (const io::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("give the unit's db.xml"), std::string::npos);
  }
  o.calib = tempPath("db.xml");
  std::ofstream(o.calib) << "<not a calibration/>\n";
  try {
    mrptio::importRecording(o, out);
    ADD_FAILURE() << "no error";
  } catch (const io::FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("not a Velodyne calibration"), std::string::npos)
        << e.what();
  }
  o.calib.clear();
  o.dual = "both";
  EXPECT_THROW(mrptio::importRecording(o, out), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(out));
  EXPECT_FALSE(std::filesystem::exists(out + ".partial"));
  std::filesystem::remove(o.input);
  std::filesystem::remove(tempPath("calib.yaml"));
  std::filesystem::remove(tempPath("db.xml"));
}

}  // namespace
