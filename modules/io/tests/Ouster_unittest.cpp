// SPDX-License-Identifier: BSD-3-Clause
// Ouster pcap + metadata reader on hand-made inputs: a 4-row x 16-column sensor, 4 columns per
// packet, pcap files written byte by byte (Ethernet / IPv4 / UDP, one fragmented datagram), the
// three packet profiles, exact expected values, and malformed inputs.
#include <dynobj/io/FormatError.h>
#include <dynobj/io/OusterPcapReader.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include "PcapTestFiles.h"

using namespace dynobj::io;
using Json = nlohmann::json;
using pcap_test::Pcap;
using pcap_test::put;

namespace {

constexpr int kRows = 4, kCols = 16, kPerPacket = 4;

std::string tempPath(const std::string& name) {
  return pcap_test::tempPath("ouster", name);
}

// The sensor: beam azimuths match the shifts (2 pi shift / W - azimuth = 0 for every row), so
// the Eq. (1) column of destaggered column c is (16 - c) mod 16.
Json metaJson(const std::string& profile) {
  return Json{{"prod_line", "OS-1-16"},
              {"build_rev", "v2.3.0"},
              {"prod_sn", "123456789"},
              {"initialization_id", 4242},
              {"lidar_mode", "16x10"},
              {"beam_altitude_angles", {30.0, 20.0, 10.0, 0.0}},
              {"beam_azimuth_angles", {0.0, 22.5, 45.0, 67.5}},
              {"lidar_origin_to_beam_origin_mm", 10.0},
              {"lidar_to_sensor_transform", {-1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1, 36.18, 0, 0, 0, 1}},
              {"udp_port_lidar", 7502},
              {"data_format",
               {{"pixels_per_column", kRows},
                {"columns_per_frame", kCols},
                {"columns_per_packet", kPerPacket},
                {"pixel_shift_by_row", {0, 1, 2, 3}},
                {"column_window", {0, kCols - 1}},
                {"udp_profile_lidar", profile}}}};
}

OusterMetadata metaOf(const Json& j) {
  const std::string path = tempPath("meta.json");
  std::ofstream(path) << j.dump();
  return OusterMetadata::load(path);
}

struct Pixel {
  std::uint32_t range;  // mm
  std::uint16_t refl, signal, nir;
};
// Expected values of pixel (row u, measurement id m) in frame f; (2, 5) has no return.
Pixel pixelOf(int u, int m, int f) {
  if (u == 2 && m == 5) return {0, 0, 0, 0};
  return {static_cast<std::uint32_t>(8 * (125 + 10 * u + m + 20 * f)),
          static_cast<std::uint16_t>(16 * u + m), static_cast<std::uint16_t>(1000 + 16 * u + m),
          static_cast<std::uint16_t>(2000 + u)};
}

// One lidar UDP payload with the columns first_mid .. first_mid + 3 of frame f.
std::string lidarPacket(const std::string& profile, int frame_id, int first_mid, int f,
                        int invalid_mid = -1, std::uint64_t serial = 123456789) {
  std::string s;
  const bool legacy = profile == "LEGACY", lb = profile == "RNG15_RFL8_NIR8";
  if (!legacy) {
    put(s, 1, 2), put(s, frame_id, 2), put(s, 4242, 3), put(s, serial, 5);
    s.resize(32, '\0');
  }
  for (int m = first_mid; m < first_mid + kPerPacket; m++) {
    put(s, 1000000000ULL + 100000000ULL * f + 1000ULL * m, 8);
    put(s, m, 2);
    if (legacy) put(s, frame_id, 2), put(s, 88 * m, 4);
    if (!legacy) put(s, m == invalid_mid ? 0 : 1, 2);
    for (int u = 0; u < kRows; u++) {
      const Pixel p = pixelOf(u, m, f);
      if (lb) {
        put(s, (p.range / 8) | 0x8000, 2), put(s, p.refl, 1), put(s, p.nir / 16 + u, 1);
      } else {
        put(s, p.range | (legacy ? 0xF00000u : 0xF80000u), 4);  // flag bits above the range
        put(s, legacy ? p.refl + 300 : p.refl, 2), put(s, p.signal, 2), put(s, p.nir, 2);
        put(s, 0, 2);
      }
    }
    if (legacy) put(s, m == invalid_mid ? 0 : 0xFFFFFFFFu, 4);
  }
  if (!legacy) s.append(32, '\0');
  return s;
}

// frames full frames of `profile` (frame ids 7, 8, ...), then the first packet of one more.
Pcap capture(const std::string& profile, int frames, bool with_partial = true) {
  Pcap p;
  for (int f = 0; f <= frames; f++) {
    for (int k = 0; k < kCols / kPerPacket; k++) {
      if (f == frames && (!with_partial || k > 0)) break;
      p.udp(7502, lidarPacket(profile, 7 + f, k * kPerPacket, f), f == 0 && k == 1);
      if (k == 2) p.udp(7503, std::string(48, '\x01'));  // IMU
    }
  }
  p.record(Pcap::ethernet(std::string(28, '\0'), 0x0806));  // ARP
  return p;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const FormatError& e) {
    return e.what();
  }
  return "(no error)";
}

std::vector<OusterScan> readAll(const std::string& path, const OusterMetadata& meta,
                                OusterPcapReader::Stats* stats = nullptr) {
  OusterPcapReader reader(path, meta);
  std::vector<OusterScan> scans;
  OusterScan s;
  while (reader.next(s)) scans.push_back(s);
  if (stats) *stats = reader.stats();
  return scans;
}

// Checks frame f of a capture against pixelOf(): destaggered images and the organized cloud.
void expectFrame(const OusterScan& s, int f, const std::string& profile) {
  const std::vector<int> shift = {0, 1, 2, 3};
  EXPECT_EQ(s.frame_id, 7u + f);
  EXPECT_EQ(s.columns_valid, kCols);
  EXPECT_EQ(s.timestamp_ns, 1000000000LL + 100000000LL * f);
  EXPECT_EQ(s.capture_time_ns, 1700000000LL * 1000000000LL);
  std::size_t returns = 0;
  for (int u = 0; u < kRows; u++) {
    for (int m = 0; m < kCols; m++) {
      const int c = (m + shift[static_cast<std::size_t>(u)]) % kCols;
      const Pixel p = pixelOf(u, m, f);
      returns += p.range != 0;
      ASSERT_EQ(s.range_mm(u, c), static_cast<std::int32_t>(p.range)) << u << "," << m;
      if (profile == "RNG15_RFL8_NIR8") {
        EXPECT_EQ(s.near_ir(u, c), (p.nir / 16 + u) * 16);
        EXPECT_TRUE(s.signal.empty());
      } else {
        EXPECT_EQ(s.signal(u, c), p.signal);
        EXPECT_EQ(s.near_ir(u, c), p.nir);
      }
      EXPECT_EQ(s.reflectivity(u, c), profile == "LEGACY" ? p.refl + 300 : p.refl);
    }
  }
  ASSERT_EQ(s.cloud.size(), returns);
  ASSERT_NO_THROW(s.cloud.validate());
  for (std::size_t i = 0; i < s.cloud.size(); i++) {
    const int u = s.cloud.row[i], c = (kCols - s.cloud.col[i]) % kCols;
    const Pixel p = pixelOf(u, (c - shift[static_cast<std::size_t>(u)] + kCols) % kCols, f);
    ASSERT_NE(p.range, 0u);
    EXPECT_EQ(s.cloud.intensity[i], profile == "RNG15_RFL8_NIR8" ? p.refl : p.signal);
  }
}

}  // namespace

TEST(OusterMetadata, ReadsTheSdkJson) {
  const OusterMetadata m = metaOf(metaJson("RNG19_RFL8_SIG16_NIR16"));
  EXPECT_EQ(m.prod_line, "OS-1-16");
  EXPECT_EQ(m.firmware, "v2.3.0");
  EXPECT_EQ(m.rows, kRows);
  EXPECT_EQ(m.cols, kCols);
  EXPECT_EQ(m.pixel_shift_by_row, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_DOUBLE_EQ(m.lidar_to_sensor(2, 3), 36.18);
  EXPECT_EQ(m.serial_number, 123456789u);
  EXPECT_EQ(m.lidarPacketSize(), 32u + 4 * (12 + 4 * 12) + 32);
  EXPECT_EQ(metaOf(metaJson("LEGACY")).lidarPacketSize(), 4u * (16 + 4 * 12 + 4));
  EXPECT_EQ(metaOf(metaJson("RNG15_RFL8_NIR8")).lidarPacketSize(), 32u + 4 * (12 + 4 * 4) + 32);
  EXPECT_EQ(m.eq1ColumnBase(), 0);
  const auto sensor = m.sensorModel();
  EXPECT_EQ(sensor.model, "OS-1-16");
  EXPECT_NEAR(sensor.beam_elevations[1], 20.0 * M_PI / 180, 1e-12);
  EXPECT_DOUBLE_EQ(sensor.max_range, 120.0);
  EXPECT_DOUBLE_EQ(sensor.frequency, 10.0);
  EXPECT_NO_THROW(sensor.validate());
}

TEST(OusterMetadata, ReducedJsonTakesTheSdkDefaults) {
  Json j = {{"lidar_mode", "512x20"},
            {"beam_altitude_angles", {8, 6, 4, 2, 0, -2, -4, -6}},
            {"beam_azimuth_angles", {3, 1, -1, -3, 3, 1, -1, -3}}};
  const OusterMetadata m = metaOf(j);
  EXPECT_EQ(m.rows, 8);
  EXPECT_EQ(m.cols, 512);
  EXPECT_EQ(m.pixel_shift_by_row, (std::vector<int>{9, 6, 3, 0, 9, 6, 3, 0}));
  EXPECT_EQ(m.profile, "LEGACY");
  EXPECT_EQ(m.column_window_last, 511);
  EXPECT_DOUBLE_EQ(m.lidar_origin_to_beam_origin_mm, 12.163);
  EXPECT_DOUBLE_EQ(m.frequency_hz, 20.0);
  EXPECT_EQ(m.sensorModel().model, "Ouster");
}

TEST(OusterMetadata, NestedJsonOfNewerSdks) {
  const Json flat = metaJson("RNG15_RFL8_NIR8");
  Json nested = {
      {"sensor_info", {{"prod_line", "OS-0-16"}}},
      {"config_params", {{"lidar_mode", "16x10"}}},
      {"beam_intrinsics",
       {{"beam_altitude_angles", flat["beam_altitude_angles"]},
        {"beam_azimuth_angles", flat["beam_azimuth_angles"]},
        {"beam_to_lidar_transform", {1, 0, 0, 27.67, 0, 1, 0, 0, 0, 0, 1, 5, 0, 0, 0, 1}}}},
      {"lidar_data_format", flat["data_format"]}};
  const OusterMetadata m = metaOf(nested);
  EXPECT_EQ(m.profile, "RNG15_RFL8_NIR8");
  EXPECT_DOUBLE_EQ(m.lidar_origin_to_beam_origin_mm, 27.67);
  EXPECT_DOUBLE_EQ(m.beam_origin_z_mm, 5.0);
  EXPECT_DOUBLE_EQ(m.sensorModel().max_range, 75.0);
}

TEST(OusterMetadata, ErrorsNameTheKey) {
  const auto err = [](const std::function<void(Json&)>& edit) {
    Json j = metaJson("LEGACY");
    edit(j);
    return errorOf([&] { metaOf(j); });
  };
  EXPECT_NE(
      err([](Json& j) { j.erase("beam_azimuth_angles"); }).find("beam_azimuth_angles: missing key"),
      std::string::npos);
  EXPECT_NE(err([](Json& j) {
              j["data_format"].erase("pixels_per_column");
            }).find("data_format.pixels_per_column: missing key"),
            std::string::npos);
  EXPECT_NE(err([](Json& j) {
              j["beam_altitude_angles"].push_back(-5.0);
            }).find("beam_altitude_angles: has 5 entries (pixels_per_column = 4)"),
            std::string::npos);
  EXPECT_NE(err([](Json& j) {
              j["data_format"]["udp_profile_lidar"] = "RNG19_RFL8_SIG16_NIR16_DUAL";
            }).find("unsupported profile 'RNG19_RFL8_SIG16_NIR16_DUAL'"),
            std::string::npos);
  EXPECT_NE(err([](Json& j) {
              j["data_format"]["pixel_shift_by_row"][2] = 16;
            }).find("pixel_shift_by_row[2]: 16 is out of range"),
            std::string::npos);
  EXPECT_NE(err([](Json& j) {
              j["data_format"]["columns_per_frame"] = 32;
            }).find("but lidar_mode is 16x10"),
            std::string::npos);
  EXPECT_NE(err([](Json& j) { j["lidar_mode"] = "fast"; }).find("lidar_mode: 'fast'"),
            std::string::npos);
  EXPECT_NE(
      err([](Json& j) { j["beam_altitude_angles"][1] = 40.0; }).find("not strictly decreasing"),
      std::string::npos);
  const std::string bad = tempPath("bad.json");
  std::ofstream(bad) << "{\"lidar_mode\": ";
  EXPECT_NE(errorOf([&] { OusterMetadata::load(bad); }).find(bad + ": not valid JSON"),
            std::string::npos);
  EXPECT_NE(errorOf([] { OusterMetadata::load("/nonexistent/meta.json"); }).find("cannot open"),
            std::string::npos);
}

TEST(OusterPcap, SingleReturnProfileWithFragmentedPacket) {
  const std::string profile = "RNG19_RFL8_SIG16_NIR16";
  OusterPcapReader::Stats st;
  const auto scans =
      readAll(capture(profile, 2).save(tempPath("single.pcap")), metaOf(metaJson(profile)), &st);
  ASSERT_EQ(scans.size(), 2u);
  expectFrame(scans[0], 0, profile);
  expectFrame(scans[1], 1, profile);
  EXPECT_EQ(scans[0].intensity_field, "signal");
  EXPECT_EQ(st.frames, 2u);
  EXPECT_EQ(st.partial_frames_skipped, 1u);  // 4 of 16 columns
  EXPECT_EQ(st.lidar_packets, 9u);
  EXPECT_EQ(st.other_packets, 3u);  // 2 IMU + 1 ARP
  EXPECT_EQ(st.fragments_reassembled, 1u);
  EXPECT_EQ(st.packets, 13u);  // 9 lidar (one in two records) + 2 IMU + ARP
  EXPECT_EQ(st.bad_packets, 0u);

  // xyz by hand from the LUT formula (beam origin n = 10 mm, lidar_to_sensor = yaw 180 deg +
  // 36.18 mm): pixel (row 0, measurement id 0): encoder 2 pi, altitude 30 deg, azimuth 0,
  // range 1000 mm. lidar xyz = r (cos30, 0, sin30) + n (1 - cos30, 0, -sin30)
  // = (866.0254 + 1.3397, 0, 500 - 5) mm -> sensor (-0.8673651, 0, 0.495 + 0.03618).
  // Pixel (0, 4): encoder 3 pi / 2, range 1032 mm: lidar (0, -(1032 - 10) cos30 - 10, 516 - 5)
  // mm -> sensor (0, 0.8950780, 0.54718). Destaggered columns 0, 4 -> Eq. (1) columns 0, 12.
  const auto& cl = scans[0].cloud;
  int found = 0;
  for (std::size_t i = 0; i < cl.size(); i++) {
    if (cl.row[i] != 0 || (cl.col[i] != 0 && cl.col[i] != 12)) continue;
    const bool first = cl.col[i] == 0;
    EXPECT_NEAR(cl.x[i], first ? -0.8673651 : 0.0, 2e-6);
    EXPECT_NEAR(cl.y[i], first ? 0.0 : 0.8950780, 2e-6);
    EXPECT_NEAR(cl.z[i], first ? 0.53118 : 0.54718, 2e-6);
    found++;
  }
  EXPECT_EQ(found, 2);
}

TEST(OusterPcap, LegacyProfileFramesByFrameIdAndByWrap) {
  Pcap p = capture("LEGACY", 1, false);
  for (int k = 0; k < kCols / kPerPacket; k++)  // frame 1 again, same frame_id as frame 0
    p.udp(7502, lidarPacket("LEGACY", 7, k * kPerPacket, 1, k == 3 ? 13 : -1));
  OusterPcapReader::Stats st;
  const auto scans = readAll(p.save(tempPath("legacy.pcap")), metaOf(metaJson("LEGACY")), &st);
  ASSERT_EQ(scans.size(), 2u);
  expectFrame(scans[0], 0, "LEGACY");  // range masked to 20 bits, 16-bit reflectivity
  EXPECT_EQ(scans[0].intensity_field, "signal");
  EXPECT_EQ(scans[1].columns_valid, kCols - 1);  // status 0 on measurement id 13
  EXPECT_EQ(scans[1].range_mm(0, 13), 0);
  EXPECT_EQ(scans[1].range_mm(0, 12), static_cast<std::int32_t>(pixelOf(0, 12, 1).range));
}

TEST(OusterPcap, LowBandwidthProfile) {
  const std::string profile = "RNG15_RFL8_NIR8";
  const auto scans =
      readAll(capture(profile, 1).save(tempPath("lb.pcap")), metaOf(metaJson(profile)));
  ASSERT_EQ(scans.size(), 1u);
  expectFrame(scans[0], 0, profile);  // range x 8 mm (flag bit 15 masked), near-IR x 16
  EXPECT_EQ(scans[0].intensity_field, "reflectivity");
}

TEST(OusterMalformed, PacketProblemsNameThePacket) {
  const auto meta = metaOf(metaJson("RNG15_RFL8_NIR8"));
  Pcap cut;  // second lidar packet cut by the snap length
  cut.udp(7502, lidarPacket("RNG15_RFL8_NIR8", 7, 0, 0));
  cut.udp(7502, lidarPacket("RNG15_RFL8_NIR8", 7, 4, 0), false, 100);
  EXPECT_NE(errorOf([&] {
              readAll(cut.save(tempPath("cut.pcap")), meta);
            }).find("packet 2: captured 58 of 176 bytes of a lidar packet"),
            std::string::npos);
  // RNG19 packets with RNG15 metadata: wrong size.
  EXPECT_NE(
      errorOf(
          [&] { readAll(capture("RNG19_RFL8_SIG16_NIR16", 1).save(tempPath("size.pcap")), meta); })
          .find("packet 1: lidar packet of 304 bytes, but profile RNG15_RFL8_NIR8 with 4 rows "
                "and 4 columns per packet expects 176 bytes"),
      std::string::npos);
  Pcap other;  // metadata of another sensor
  other.udp(7502, lidarPacket("RNG15_RFL8_NIR8", 7, 0, 0, -1, 987654321));
  EXPECT_NE(errorOf([&] {
              readAll(other.save(tempPath("sn.pcap")), meta);
            }).find("packet 1: sensor serial"),
            std::string::npos);
  Pcap mid;  // measurement id 16 >= 16 columns
  mid.udp(7502, lidarPacket("RNG15_RFL8_NIR8", 7, 13, 0));
  EXPECT_NE(
      errorOf([&] { readAll(mid.save(tempPath("mid.pcap")), meta); }).find("measurement id 16"),
      std::string::npos);
  Pcap imu;  // only IMU packets
  imu.udp(7503, std::string(48, '\0'));
  EXPECT_NE(errorOf([&] {
              readAll(imu.save(tempPath("imu.pcap")), meta);
            }).find("no UDP packets on the lidar port 7502; ports seen: 7503 (1)"),
            std::string::npos);
}

TEST(OusterMalformed, CaptureCutAtTheEndIsCounted) {
  const std::string profile = "RNG15_RFL8_NIR8";
  Pcap p = capture(profile, 1, false);
  p.bytes += p.bytes.substr(24, 100);  // a record header and part of its data
  OusterPcapReader::Stats st;
  const auto scans = readAll(p.save(tempPath("end.pcap")), metaOf(metaJson(profile)), &st);
  EXPECT_EQ(scans.size(), 1u);
  EXPECT_EQ(st.bad_packets, 1u);
}

TEST(OusterMalformed, NotAPcapFile) {
  const auto meta = metaOf(metaJson("LEGACY"));
  const std::string path = tempPath("not.pcap");
  std::ofstream(path) << "# this is a text file, not a capture\n";
  EXPECT_NE(errorOf([&] { OusterPcapReader r(path, meta); }).find(path + ": not a readable pcap"),
            std::string::npos);
  EXPECT_NE(
      errorOf([&] { OusterPcapReader r("/nonexistent.pcap", meta); }).find("/nonexistent.pcap: "),
      std::string::npos);
}

TEST(OusterMalformed, DamagedCapturesNeverCrash) {
  const std::string profile = "RNG19_RFL8_SIG16_NIR16";
  const auto meta = metaOf(metaJson(profile));
  const std::string good = capture(profile, 2).bytes;
  std::mt19937 rng(42);
  int errors = 0, ok = 0;
  for (int trial = 0; trial < 300; trial++) {
    Pcap p;
    p.bytes = good;
    if (trial % 3 == 0) p.bytes.resize(rng() % good.size());
    for (int k = 0; k < 1 + trial % 5; k++)
      p.bytes[24 + rng() % (good.size() - 24)] = static_cast<char>(rng());
    const std::string path = p.save(tempPath("fuzz.pcap"));
    try {
      readAll(path, meta);
      ok++;
    } catch (const FormatError&) {
      errors++;
    }
  }
  EXPECT_EQ(ok + errors, 300);
  EXPECT_GT(errors, 0);
}
