// SPDX-License-Identifier: BSD-3-Clause
// Ouster reader on the real captures in ../shared/realdata/ouster (Ouster SDK test pcaps, not
// part of this project): frame counts, image size, the Eq. (1) column layout, planar floors.
// Skipped where that folder is absent. Prints points per frame, decode time, plane RMS.
#include <dynobj/io/OusterPcapReader.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>

using namespace dynobj::io;

namespace {

const std::string kDir = DYNOBJ_SOURCE_DIR "/../shared/realdata/ouster/";

struct Capture {
  const char* pcap;
  const char* json;
  std::size_t frames;
  const char* profile;
  const char* intensity;
  int rows;
};
const Capture kCaptures[] = {
    {"OS-1-64_1024x10_fw20.pcap", "OS-1-64_sensor_config_reduced.json", 1, "LEGACY", "signal", 64},
    {"OS-1-128_v2.3.0_1024x10_lb_n3.pcap", "OS-1-128_v2.3.0_1024x10.json", 3, "RNG15_RFL8_NIR8",
     "reflectivity", 128},
    {"OS-2-128-U1_v2.3.0_1024x10.pcap", "OS-2-128-U1_v2.3.0_1024x10.json", 1,
     "RNG19_RFL8_SIG16_NIR16", "signal", 128},
    {"OS-0-128-U1_v2.3.0_1024x10.pcap", "OS-0-128-U1_v2.3.0_1024x10.json", 1, "RNG15_RFL8_NIR8",
     "reflectivity", 128},
};

#define SKIP_WITHOUT_REAL_DATA()            \
  if (!std::filesystem::is_directory(kDir)) \
  GTEST_SKIP() << "../shared/realdata/ouster not found: real-capture tests skipped"

struct Decoded {
  OusterMetadata meta;
  std::vector<OusterScan> scans;
  OusterPcapReader::Stats stats;
  double ms_per_frame = 0;
};

Decoded decode(const Capture& c) {
  Decoded d;
  d.meta = OusterMetadata::load(kDir + c.json);
  const auto t0 = std::chrono::steady_clock::now();
  OusterPcapReader reader(kDir + c.pcap, d.meta);
  OusterScan s;
  while (reader.next(s)) d.scans.push_back(s);
  const std::chrono::duration<double, std::milli> dt = std::chrono::steady_clock::now() - t0;
  d.stats = reader.stats();
  d.ms_per_frame = d.scans.empty() ? 0 : dt.count() / static_cast<double>(d.scans.size());
  return d;
}

struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0;             ///< plane: normal . p + d = 0
  std::size_t inliers = 0;  ///< points within `band`
  double rms = 0;           ///< RMS distance of the inliers [m]
  double patch_rms = 0;  ///< median over 1 m x 1 m patches of the inliers' RMS to their own plane
};

// Largest plane (RANSAC, then least squares) among the points within 20 m; `floor`: only points
// below z = -0.5 m and near-horizontal planes.
Plane largestPlane(const dynobj::core::PointCloud& cl, bool floor, double band) {
  std::vector<Eigen::Vector3d> pts;
  for (std::size_t i = 0; i < cl.size(); i++) {
    const Eigen::Vector3d p(cl.x[i], cl.y[i], cl.z[i]);
    if (p.norm() > 0.3 && p.head<2>().norm() < 20 && (!floor || p.z() < -0.5)) pts.push_back(p);
  }
  Plane pl;
  if (pts.size() < 100) return pl;
  const auto inliersOf = [&](const Eigen::Vector3d& n, double d) {
    std::vector<Eigen::Vector3d> in;
    for (const auto& p : pts)
      if (std::abs(n.dot(p) + d) < band) in.push_back(p);
    return in;
  };
  std::mt19937 rng(7);
  std::uniform_int_distribution<std::size_t> pick(0, pts.size() - 1);
  for (int it = 0; it < 1500; it++) {
    const Eigen::Vector3d a = pts[pick(rng)], b = pts[pick(rng)], c = pts[pick(rng)];
    Eigen::Vector3d n = (b - a).cross(c - a);
    if (n.norm() < 1e-6 || (floor && std::abs(n.normalized().z()) < 0.9)) continue;
    n.normalize();
    const std::size_t count = inliersOf(n, -n.dot(a)).size();
    if (count > pl.inliers) pl.inliers = count, pl.normal = n, pl.d = -n.dot(a);
  }
  const auto fit = [](const std::vector<Eigen::Vector3d>& in, Eigen::Vector3d& n, double& d) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (const auto& p : in) mean += p;
    mean /= static_cast<double>(in.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const auto& p : in) cov += (p - mean) * (p - mean).transpose();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
    n = es.eigenvectors().col(0);
    d = -n.dot(mean);
    return std::sqrt(std::max(0.0, es.eigenvalues()(0)) / static_cast<double>(in.size()));
  };
  std::vector<Eigen::Vector3d> in;
  for (int refine = 0; refine < 3; refine++) {
    in = inliersOf(pl.normal, pl.d);
    if (in.size() < 3) return Plane{};
    fit(in, pl.normal, pl.d);
  }
  in = inliersOf(pl.normal, pl.d);
  pl.inliers = in.size();
  double sum2 = 0;
  for (const auto& p : in) sum2 += std::pow(pl.normal.dot(p) + pl.d, 2);
  pl.rms = std::sqrt(sum2 / static_cast<double>(in.size()));
  // Local flatness: 1 m patches along the plane (the floor of a street need not be one plane).
  const Eigen::Vector3d e1 = pl.normal.unitOrthogonal(), e2 = pl.normal.cross(e1);
  std::map<std::pair<long, long>, std::vector<Eigen::Vector3d>> patches;
  for (const auto& p : in)
    patches[{std::lround(std::floor(p.dot(e1))), std::lround(std::floor(p.dot(e2)))}].push_back(p);
  std::vector<double> patch_rms;
  for (const auto& [cell, v] : patches) {
    Eigen::Vector3d n;
    double d = 0;
    if (v.size() >= 30) patch_rms.push_back(fit(v, n, d));
  }
  if (!patch_rms.empty()) {
    std::nth_element(patch_rms.begin(), patch_rms.begin() + static_cast<long>(patch_rms.size() / 2),
                     patch_rms.end());
    pl.patch_rms = patch_rms[patch_rms.size() / 2];
  }
  return pl;
}

}  // namespace

TEST(OusterReal, DecodesEveryCapture) {
  SKIP_WITHOUT_REAL_DATA();
  for (const Capture& c : kCaptures) {
    SCOPED_TRACE(c.pcap);
    const Decoded d = decode(c);
    EXPECT_EQ(d.meta.rows, c.rows);
    EXPECT_EQ(d.meta.cols, 1024);
    EXPECT_EQ(d.meta.profile, c.profile);
    ASSERT_EQ(d.scans.size(), c.frames);
    EXPECT_EQ(d.stats.frames, c.frames);
    EXPECT_EQ(d.stats.lidar_packets, 64 * c.frames);
    EXPECT_EQ(d.stats.partial_frames_skipped, 0u);
    EXPECT_EQ(d.stats.bad_packets, 0u);
    EXPECT_EQ(d.stats.init_id_mismatches, 0u);
    for (const OusterScan& s : d.scans) {
      EXPECT_EQ(s.range_mm.rows, c.rows);
      EXPECT_EQ(s.range_mm.cols, 1024);
      EXPECT_EQ(s.columns_valid, 1024);
      EXPECT_EQ(s.intensity_field, c.intensity);
      EXPECT_EQ(s.signal.empty(), std::string(c.intensity) == "reflectivity");
      EXPECT_NO_THROW(s.cloud.validate());
      EXPECT_EQ(s.cloud.size(), static_cast<std::size_t>(cv::countNonZero(s.range_mm)));
      EXPECT_GT(s.cloud.size(), 1024u * static_cast<std::size_t>(c.rows) / 5);
      std::printf(
          "[ figures  ] %s frame %u: %zu points (%.1f %% of pixels), %zu packets, "
          "%.1f ms/frame\n",
          c.pcap, s.frame_id, s.cloud.size(),
          100.0 * static_cast<double>(s.cloud.size()) / (1024.0 * c.rows), d.stats.packets,
          d.ms_per_frame);
    }
  }
}

TEST(OusterReal, ColumnsFollowEq1) {
  SKIP_WITHOUT_REAL_DATA();
  for (const Capture& c : kCaptures) {
    SCOPED_TRACE(c.pcap);
    const Decoded d = decode(c);
    const int w = d.meta.cols;
    for (const OusterScan& s : d.scans) {
      std::size_t near = 0, exact = 0;
      const auto& cl = s.cloud;
      for (std::size_t i = 0; i < cl.size(); i++) {
        const double u = (std::atan2(cl.y[i], cl.x[i]) + M_PI) / (2 * M_PI) * w;
        const int expected = static_cast<int>(std::floor(u)) % w;
        const int diff = std::abs(cl.col[i] - expected);
        const int circular = std::min(diff, w - diff);
        near += circular <= 1;
        exact += circular == 0;
      }
      const double pct = 100.0 * static_cast<double>(near) / static_cast<double>(cl.size());
      std::printf(
          "[ figures  ] %s frame %u: col within +-1 of Eq. (1) for %.2f %% (exact %.2f %%)\n",
          c.pcap, s.frame_id, pct,
          100.0 * static_cast<double>(exact) / static_cast<double>(cl.size()));
      EXPECT_GE(pct, 95.0);
    }
  }
}

// Geometry check: with the beam angles of the JSON, the ground (or, indoors, a wall) is a plane.
// Wrong beam altitudes would bend it into a cone; a wrong transform would tilt or lift it.
TEST(OusterReal, GroundIsPlanar) {
  SKIP_WITHOUT_REAL_DATA();
  for (const Capture& c : kCaptures) {
    SCOPED_TRACE(c.pcap);
    const Decoded d = decode(c);
    // The OS-1-64 capture is a small room with hardly any floor in view: its largest plane
    // within 1 cm is a wall 1.2 m away (shelves 8 cm in front of it make a wider band ambiguous).
    const bool indoor = c.rows == 64;
    const Plane pl = largestPlane(d.scans.front().cloud, !indoor, indoor ? 0.01 : 0.05);
    std::printf(
        "[ figures  ] %s: %s: %zu inliers within %.0f cm, RMS %.4f m, median RMS of 1 m "
        "patches %.4f m, normal (%.3f %.3f %.3f), offset %.3f m\n",
        c.pcap, indoor ? "wall" : "floor", pl.inliers, indoor ? 1.0 : 5.0, pl.rms, pl.patch_rms,
        pl.normal.x(), pl.normal.y(), pl.normal.z(), pl.d);
    EXPECT_GT(pl.inliers, indoor ? 1000u : 5000u);
    EXPECT_LT(pl.rms, indoor ? 0.008 : 0.03);
    EXPECT_LT(pl.patch_rms, 0.015);
    if (indoor) {
      EXPECT_LT(std::abs(pl.normal.z()), 0.05);  // vertical
    } else {
      EXPECT_GT(std::abs(pl.normal.z()), 0.99);
      EXPECT_GT(std::abs(pl.d), 1.0);  // the sensor is 1.9 m above the ground in these captures
      EXPECT_LT(std::abs(pl.d), 3.0);
    }
  }
}

TEST(OusterReal, LegacyCaptureWithReducedMetadata) {
  SKIP_WITHOUT_REAL_DATA();
  const Decoded d = decode(kCaptures[0]);
  EXPECT_EQ(d.meta.lidar_mode, "1024x10");
  EXPECT_EQ(d.meta.columns_per_packet, 16);
  for (int u = 0; u < 64; u++)
    EXPECT_EQ(d.meta.pixel_shift_by_row[static_cast<std::size_t>(u)], 18 - 6 * (u % 4));
  EXPECT_EQ(d.stats.other_packets, 11u);  // IMU
  double max_refl = 0;
  cv::minMaxLoc(d.scans.front().reflectivity, nullptr, &max_refl);
  EXPECT_GT(max_refl, 255.0);  // 16-bit reflectivity on FW 2.0
}

TEST(OusterReal, LowBandwidthSequenceHasThreeConsecutiveFrames) {
  SKIP_WITHOUT_REAL_DATA();
  const Decoded d = decode(kCaptures[1]);
  ASSERT_EQ(d.scans.size(), 3u);
  EXPECT_EQ(d.scans[0].capture_time_ns / 1000000000LL, 1650410295);  // pcap time, 2022-04-19
  for (std::size_t i = 1; i < 3; i++) {
    EXPECT_EQ(d.scans[i].frame_id, d.scans[i - 1].frame_id + 1);
    EXPECT_NEAR(static_cast<double>(d.scans[i].timestamp_ns - d.scans[i - 1].timestamp_ns), 1e8,
                1e6);
    EXPECT_NEAR(static_cast<double>(d.scans[i].capture_time_ns - d.scans[i - 1].capture_time_ns),
                1e8, 2e7);
  }
}
