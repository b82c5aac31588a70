// SPDX-License-Identifier: BSD-3-Clause
// Velodyne pcap reader on hand-made packets: VLP-16 and HDL-32E sweeps with every point checked
// against the packet format (range, azimuth with the firing-delay interpolation, elevation from
// the beam table, per-point time, row by elevation, Eq. (1) column), HDL-64E and VLS-128 banks
// with a unit calibration's azimuth corrections, dual returns (strongest / last), and the
// errors: not a Velodyne capture, no data packets, wrong sizes, snap length, unknown and mixed
// models, a model whose timing does not fit.
#include <dynobj/core/SphericalProjection.h>
#include <dynobj/io/FormatError.h>
#include <dynobj/io/VelodynePcapReader.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>

#include "PcapTestFiles.h"

using namespace dynobj::io;
using pcap_test::put;

namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr std::int64_t kCapture0 = 1700000000LL * 1000000000LL;

std::string tempPath(const std::string& name) {
  return pcap_test::tempPath("velodyne", name);
}

struct Return {
  std::uint16_t distance;  // 2 mm (4 mm for VLP-32C / VLS-128) units
  std::uint8_t intensity;
};
/// The return of channel `ch` of block `b` in packet `p`.
using ChannelFn = std::function<Return(int p, int b, int ch)>;

struct Spec {
  std::vector<std::uint16_t> ids = std::vector<std::uint16_t>(12, 0xEEFF);
  /// Azimuth [0.01 deg] of block b of packet p.
  std::function<int(int p, int b)> azimuth;
  ChannelFn channel;
  double period_us = 0;  ///< sensor time between packets
  std::uint8_t mode = 0x37, product = 0x22;
};

std::string packet(const Spec& s, int p) {
  std::string out;
  for (int b = 0; b < 12; b++) {
    put(out, s.ids[static_cast<std::size_t>(b)], 2);
    put(out, static_cast<std::uint64_t>(s.azimuth(p, b) % 36000), 2);
    for (int ch = 0; ch < 32; ch++) {
      const Return r = s.channel(p, b, ch);
      put(out, r.distance, 2), put(out, r.intensity, 1);
    }
  }
  put(out, static_cast<std::uint64_t>(std::llround(1000 + p * s.period_us)), 4);
  put(out, s.mode, 1), put(out, s.product, 1);
  return out;
}

std::int64_t captureTime(const Spec& s, int p) {
  return kCapture0 + std::llround(p * s.period_us) * 1000;
}

std::vector<VelodyneScan> decodeAll(const Spec& s, int packets, VelodyneOptions o = {},
                                    VelodyneDecoder* out = nullptr) {
  VelodyneDecoder local(o);
  VelodyneDecoder& d = out ? *out : local;
  for (int p = 0; p < packets; p++) {
    const std::string pk = packet(s, p);
    d.addPacket(reinterpret_cast<const std::uint8_t*>(pk.data()), pk.size(),
                static_cast<std::size_t>(p + 1), "test", captureTime(s, p));
  }
  d.flush("test");
  std::vector<VelodyneScan> scans;
  VelodyneScan scan;
  while (d.popFrame(scan)) scans.push_back(scan);
  return scans;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const FormatError& e) {
    return e.what();
  }
  return "(no error)";
}

// Row of each laser id: the beam table sorted by descending elevation.
std::vector<int> rowsOf(const std::vector<double>& elevation) {
  std::vector<int> row(elevation.size());
  for (std::size_t l = 0; l < elevation.size(); l++) {
    int r = 0;
    for (double e : elevation) r += e > elevation[l];
    row[l] = r;
  }
  return row;
}

// The point every firing of a single-return sweep should give. `firing` = index in the sweep,
// `block_step` = azimuth step per block [0.01 deg], `lasers_per_firing_block` etc. from the model.
struct Expected {
  double azimuth_deg, range, elevation_deg;
  std::int64_t time_ns;
};

void expectPoint(const VelodyneScan& s, std::size_t i, const Expected& e, int row, int col,
                 float intensity) {
  const double xy = e.range * std::cos(e.elevation_deg * kDeg);
  ASSERT_LT(i, s.cloud.size());
  EXPECT_NEAR(s.cloud.x[i], xy * std::cos(e.azimuth_deg * kDeg), 1e-5) << i;
  EXPECT_NEAR(s.cloud.y[i], -xy * std::sin(e.azimuth_deg * kDeg), 1e-5) << i;
  EXPECT_NEAR(s.cloud.z[i], e.range * std::sin(e.elevation_deg * kDeg), 1e-5) << i;
  EXPECT_NEAR(s.azimuth_deg[i], e.azimuth_deg, 1e-4) << i;
  EXPECT_EQ(s.time_ns[i], e.time_ns) << i;
  EXPECT_EQ(s.cloud.row[i], row) << i;
  EXPECT_EQ(s.cloud.col[i], col) << i;
  EXPECT_EQ(s.cloud.intensity[i], intensity) << i;
}

// --- VLP-16: two firings per block, 0.2 deg per firing (0.4 per block) -> 1800 columns -------

Return vlp16Return(int p, int b, int ch) {
  const int l = ch % 16;
  if (l == 5 && b == 3) return {0, 0};  // no return
  return {static_cast<std::uint16_t>(1000 + 10 * l + (p + b) % 7),
          static_cast<std::uint8_t>(3 * l + ch / 16)};
}

Spec vlp16Spec() {
  Spec s;
  s.azimuth = [](int p, int b) { return 40 * (12 * p + b); };
  s.channel = vlp16Return;
  s.period_us = 12 * 110.592;
  s.product = 0x22;
  return s;
}

TEST(VelodyneDecoder, Vlp16SweepEveryPointExact) {
  // 75 packets = 1800 firings = one turn from azimuth 0; packet 75 starts the next turn (wrap),
  // which ends partial (one packet) and is dropped.
  VelodyneDecoder d;
  const auto scans = decodeAll(vlp16Spec(), 76, {}, &d);
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(d.partialFramesSkipped(), 1u);
  EXPECT_EQ(d.sensor().name, "VLP-16");
  EXPECT_EQ(d.modelSource(), "product id 0x22");
  EXPECT_EQ(d.cols(), 1800);
  EXPECT_NEAR(d.frequencyHz(), 0.2 / 55.296e-6 / 360.0, 1e-3);  // 10.05 Hz
  const VelodyneScan& s = scans[0];
  EXPECT_EQ(s.firings, 1800);
  EXPECT_DOUBLE_EQ(s.azimuth_span_deg, 359.8);
  EXPECT_EQ(s.timestamp_ns, kCapture0);
  EXPECT_EQ(s.no_return, 75u * 2);  // laser 5 of block 3, both firings, in each packet
  ASSERT_EQ(s.cloud.size(), 1800u * 16 - 150);
  const auto vlp16 = VelodyneSensor::of(VelodyneModel::VLP16);
  const auto row = rowsOf(vlp16.elevation_deg);
  EXPECT_EQ(row[15], 0);  // +15 deg on top
  EXPECT_EQ(row[1], 7);   // +1 deg
  EXPECT_EQ(row[14], 8);  // -1 deg
  EXPECT_EQ(row[0], 15);  // -15 deg at the bottom
  std::size_t i = 0;
  for (int p = 0; p < 75; p++) {
    for (int b = 0; b < 12; b++) {
      for (int f = 0; f < 2; f++) {
        const int k = 2 * (12 * p + b) + f;  // firing in the sweep
        for (int l = 0; l < 16; l++) {
          const Return r = vlp16Return(p, b, 16 * f + l);
          if (r.distance == 0) continue;
          // 0.4 deg per 110.592 us; laser l fires 2.304 l us after its firing started.
          const double az = 0.2 * k + 0.4 * 2.304 * l / 110.592;
          const std::int64_t t = std::llround(p * 1327.104) * 1000 + (2 * b + f) * 55296 + 2304 * l;
          expectPoint(s, i, {az, r.distance * 0.002, vlp16.elevation_deg[l], t}, row[l],
                      ((900 - k) % 1800 + 1800) % 1800, r.intensity);
          if (HasFailure()) return;
          i++;
        }
      }
    }
  }
  EXPECT_EQ(i, s.cloud.size());
  EXPECT_EQ(s.cloud.ring[0], 0u);
}

// --- HDL-32E: one firing per block, 0.16 deg per firing -> 2250 columns ----------------------

Return hdl32Return(int p, int b, int ch) {
  if (ch == 31 && p % 2 == 0) return {0, 0};
  return {static_cast<std::uint16_t>(5000 + 37 * ch + b), static_cast<std::uint8_t>(ch + p % 3)};
}

Spec hdl32Spec() {
  Spec s;
  s.azimuth = [](int p, int b) { return 16 * (12 * p + b) + 9000; };  // the turn starts at 90 deg
  s.channel = hdl32Return;
  s.period_us = 12 * 46.08;
  s.product = 0x21;
  return s;
}

TEST(VelodyneDecoder, Hdl32eSweepEveryPointExact) {
  // 2250 firings per turn; starting at 90 deg, the first sweep ends at the wrap to 0 after 1688
  // firings (270 deg: kept), the second (712 firings) is partial.
  VelodyneDecoder d;
  const auto scans = decodeAll(hdl32Spec(), 200, {}, &d);
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(d.partialFramesSkipped(), 1u);
  EXPECT_EQ(d.sensor().name, "HDL-32E");
  EXPECT_EQ(d.cols(), 2250);
  const VelodyneScan& s = scans[0];
  EXPECT_EQ(s.firings, 1688);
  const auto hdl32 = VelodyneSensor::of(VelodyneModel::HDL32E);
  const auto row = rowsOf(hdl32.elevation_deg);
  EXPECT_EQ(row[31], 0);  // +10.67 deg
  EXPECT_EQ(row[0], 31);  // -30.67 deg
  // Azimuth 90 deg (clockwise) = -90 deg in Eq. (1): column (-pi/2 + pi) / 2pi * 2250 = 562.5.
  const int c0 = 562;
  std::size_t i = 0, zeros = 0;
  for (int k = 0; k < 1688; k++) {
    const int p = k / 12, b = k % 12;
    for (int ch = 0; ch < 32; ch++) {
      const Return r = hdl32Return(p, b, ch);
      if (r.distance == 0) {
        zeros++;
        continue;
      }
      const double az = std::fmod(90.0 + 0.16 * k + 0.16 * 1.152 * ch / 46.08, 360.0);
      const std::int64_t t = std::llround(p * 552.96) * 1000 + b * 46080 + 1152 * ch;
      expectPoint(s, i, {az, r.distance * 0.002, hdl32.elevation_deg[ch], t}, row[ch],
                  ((c0 - k) % 2250 + 2250) % 2250, r.intensity);
      if (HasFailure()) return;
      i++;
    }
  }
  EXPECT_EQ(i, s.cloud.size());
  EXPECT_EQ(s.no_return, zeros);
  // Every point's Eq. (1) column (from x, y) is its column or the next one clockwise: the
  // firing delay turns the last lasers up to 0.8 column further.
  const dynobj::core::SphericalProjection eq1(d.sensorModel());
  for (std::size_t j = 0; j < s.cloud.size(); j++) {
    const int c = eq1.columnOf(s.cloud.x[j], s.cloud.y[j]);
    const int diff = ((s.cloud.col[j] - c) % 2250 + 2250) % 2250;
    ASSERT_LE(diff, 1) << j;
  }
}

TEST(VelodyneDecoder, Hdl32eWithoutFactoryBytesIsAnHdl32e) {
  Spec s = hdl32Spec();
  s.mode = 0, s.product = 0;
  VelodyneDecoder d;
  decodeAll(s, 20, {}, &d);
  EXPECT_EQ(d.sensor().name, "HDL-32E");
  EXPECT_NE(d.modelSource().find("no product id"), std::string::npos);
}

// --- Dual returns: block 2b = last return, 2b + 1 = strongest (or second strongest) ----------

// Laser l: 0 = a single return (both blocks equal); 1 = last far and weak, strongest near;
// 2 = the last is the strongest, the other block the second strongest; 3 = no return.
Return dualReturn(int /*p*/, int b, int ch) {
  const int l = ch % 16;
  const bool last = b % 2 == 0;
  switch (l % 4) {
    case 0:
      return {1000, 50};
    case 1:
      return last ? Return{4000, 10} : Return{1500, 90};
    case 2:
      return last ? Return{3000, 80} : Return{2000, 20};
    default:
      return {0, 0};
  }
}

Spec dualSpec() {
  Spec s;
  s.azimuth = [](int p, int b) { return 40 * (6 * p + b / 2); };
  s.channel = dualReturn;
  s.period_us = 6 * 110.592;
  s.mode = 0x39;
  return s;
}

TEST(VelodyneDecoder, DualReturnKeepsOneReturnPerLaser) {
  for (const DualReturn keep : {DualReturn::Strongest, DualReturn::Last}) {
    VelodyneOptions o;
    o.dual = keep;
    VelodyneDecoder d(o);
    const auto scans = decodeAll(dualSpec(), 151, o, &d);  // 150 packets = one turn
    ASSERT_EQ(scans.size(), 1u);
    EXPECT_TRUE(d.dualReturn());
    EXPECT_EQ(d.cols(), 1800);
    const VelodyneScan& s = scans[0];
    EXPECT_EQ(s.firings, 1800);
    // 12 of 16 lasers return: one point each, never two.
    ASSERT_EQ(s.cloud.size(), 1800u * 12);
    // Lasers 1, 5, 9, 13 and 2, 6, 10, 14 have two different returns per firing.
    // (in every firing decoded: 151 packets x 12 firings, the partial sweep's included).
    EXPECT_EQ(d.secondReturnsDropped(), 151u * 12 * 8);
    for (std::size_t i = 0; i < s.cloud.size(); i++) {
      const int l = s.cloud.ring[i];
      const double r = std::hypot(s.cloud.x[i], s.cloud.y[i], s.cloud.z[i]);
      const bool strongest = keep == DualReturn::Strongest;
      const double want = l % 4 == 0 ? 2.0 : l % 4 == 1 ? (strongest ? 3.0 : 8.0) : 6.0;
      const float inten = l % 4 == 0 ? 50 : l % 4 == 1 ? (strongest ? 90 : 10) : 80;
      ASSERT_NEAR(r, want, 1e-5) << i;
      ASSERT_EQ(s.cloud.intensity[i], inten) << i;
    }
    // Firing times: 12 firings per packet (6 block pairs x 2), 55.296 us apart.
    EXPECT_EQ(s.time_ns[12 * 12], std::llround(6 * 110.592) * 1000);  // packet 1, first point
  }
}

// --- Banks: HDL-64E (upper / lower) and VLS-128 (four banks) with azimuth corrections --------

TEST(VelodyneDecoder, Hdl64eNeedsItsCalibrationAndUsesIt) {
  Spec s;
  s.ids = {0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF,
           0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF};
  s.azimuth = [](int p, int b) { return 200 * (6 * p + b / 2); };  // 2 deg per firing: 180 cols
  s.channel = [](int, int b, int ch) {
    return Return{static_cast<std::uint16_t>(2500 + ch), static_cast<std::uint8_t>(b % 2)};
  };
  s.period_us = 6 * 57.6;
  s.mode = 0x11, s.product = 0x42;  // status bytes, not factory bytes
  EXPECT_NE(errorOf([&] { decodeAll(s, 2); }).find("beam angles are unit-specific"),
            std::string::npos);

  VelodyneOptions o;
  for (int l = 0; l < 64; l++) {
    o.elevation_deg.push_back(-24.0 + 0.4 * l);
    o.azimuth_correction_deg.push_back(l % 2 ? 4.0 : -4.0);  // two columns of 2 deg
  }
  o.calibration_source = "test-db.xml";
  VelodyneDecoder d(o);
  const auto scans = decodeAll(s, 31, o, &d);  // 30 packets = 180 firings = one turn
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(d.sensor().name, "HDL-64E S3");
  EXPECT_EQ(d.cols(), 180);
  const VelodyneScan& sc = scans[0];
  ASSERT_EQ(sc.cloud.size(), 180u * 64);
  // Firing 3 (packet 0, blocks 6 and 7), laser 33 = lower block channel 1: fires 1.3 us late.
  const std::size_t i = 3 * 64 + 33;
  EXPECT_EQ(sc.cloud.ring[i], 33u);
  const double az = 6.0 + 2.0 * 1.3 / 57.6 - 4.0;
  EXPECT_NEAR(sc.azimuth_deg[i], az, 1e-4);
  EXPECT_EQ(sc.time_ns[i], 3 * 57600 + 1300);
  EXPECT_NEAR(std::hypot(sc.cloud.x[i], sc.cloud.y[i], sc.cloud.z[i]), (2500 + 1) * 0.002, 1e-5);
  EXPECT_EQ(sc.cloud.row[i], 63 - 33);
  // Column: firing 3 is 3 columns clockwise of column 90 (azimuth 0), the +4 deg correction
  // turns the laser two columns back.
  EXPECT_EQ(sc.cloud.col[i], 90 - 3 + 2);
  EXPECT_EQ(sc.cloud.intensity[i], 1.0f);

  o.elevation_deg.pop_back(), o.azimuth_correction_deg.pop_back();
  EXPECT_NE(errorOf([&] { decodeAll(s, 2, o); }).find("calibration of 63 lasers"),
            std::string::npos);
}

TEST(VelodyneDecoder, Vls128FourBanksPerFiring) {
  Spec s;
  s.ids = {0xEEFF, 0xDDFF, 0xCCFF, 0xBBFF, 0xEEFF, 0xDDFF,
           0xCCFF, 0xBBFF, 0xEEFF, 0xDDFF, 0xCCFF, 0xBBFF};
  s.azimuth = [](int p, int b) { return 200 * (3 * p + b / 4); };
  s.channel = [](int, int b, int ch) {
    return Return{static_cast<std::uint16_t>(1000 + 32 * (b % 4) + ch), 7};
  };
  s.period_us = 3 * 53.3;
  s.product = 0xA1;
  VelodyneDecoder d;
  const auto scans = decodeAll(s, 61, {}, &d);  // 60 packets = 180 firings
  ASSERT_EQ(scans.size(), 1u);
  EXPECT_EQ(d.sensor().name, "VLS-128");
  const auto vls = VelodyneSensor::of(VelodyneModel::VLS128);
  const VelodyneScan& sc = scans[0];
  ASSERT_EQ(sc.cloud.size(), 180u * 128);
  // Firing 1, laser 100 (bank 3, channel 4): distance 1100 x 4 mm, fires in group 12 + 2.
  const std::size_t i = 128 + 100;
  EXPECT_NEAR(std::hypot(sc.cloud.x[i], sc.cloud.y[i], sc.cloud.z[i]), 1100 * 0.004, 1e-5);
  EXPECT_NEAR(std::asin(sc.cloud.z[i] / (1100 * 0.004)) / kDeg, vls.elevation_deg[100], 1e-4);
  EXPECT_EQ(sc.time_ns[i], 53300 + std::llround(2.665 * 14 * 1000));
  EXPECT_NEAR(sc.azimuth_deg[i], 2.0 + 2.0 * 2.665 * 14 / 53.3 - vls.azimuth_correction_deg[100],
              1e-4);
}

// --- Errors ------------------------------------------------------------------------------------

TEST(VelodyneDecoder, RefusesWhatItCannotDecode) {
  const auto first_packet_error = [](Spec s, VelodyneOptions o = {}) {
    return errorOf([&] { decodeAll(s, 12, o); });
  };
  Spec s = vlp16Spec();
  s.ids[4] = 0x1234;
  EXPECT_NE(first_packet_error(s).find("block 4 has id 0x1234"), std::string::npos);
  s = vlp16Spec();
  s.product = 0x23;
  EXPECT_NE(first_packet_error(s).find("unknown Velodyne product id 0x23"), std::string::npos);
  VelodyneOptions given;
  given.model = VelodyneModel::VLP16;
  EXPECT_EQ(first_packet_error(s, given), "(no error)");  // the model given settles it
  s = vlp16Spec();
  s.mode = 0x3B;
  EXPECT_NE(first_packet_error(s).find("unknown return mode byte 0x3B"), std::string::npos);
  // VLP-16 packets whose factory byte says HDL-32E (as the VeloView VLP-16 sample's do).
  s = vlp16Spec();
  s.product = 0x21;
  const std::string e = first_packet_error(s);
  EXPECT_NE(e.find("every 1327.0 us of sensor time, but one every 552.96 us comes from the HDL-32E "
                   "(model product id 0x21)"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("models that fit: VLP-16, Puck Hi-Res"), std::string::npos) << e;
  // Dual-return HDL-64E.
  s.ids = {0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF,
           0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF, 0xEEFF, 0xDDFF};
  s.azimuth = [](int p, int b) { return 200 * (3 * p + b / 4); };
  EXPECT_NE(first_packet_error(s).find("dual-return HDL-64E S3 captures are not supported"),
            std::string::npos);
  // Mixed models: VLP-16 packets, then one from an HDL-32E.
  s = vlp16Spec();
  s.channel = vlp16Return;
  VelodyneDecoder d;
  const std::string a = packet(s, 0);
  d.addPacket(reinterpret_cast<const std::uint8_t*>(a.data()), a.size(), 1, "cap", kCapture0);
  Spec other = hdl32Spec();
  const std::string b = packet(other, 1);
  const std::string mixed = errorOf([&] {
    d.addPacket(reinterpret_cast<const std::uint8_t*>(b.data()), b.size(), 2, "cap", kCapture0);
  });
  EXPECT_EQ(mixed,
            "cap: packet 2: product id 0x21 (HDL-32E), return mode 0x37, but the capture "
            "started with product id 0x22 (VLP-16), return mode 0x37 (mixed models or "
            "modes)");
  EXPECT_NE(errorOf([&] {
              d.addPacket(reinterpret_cast<const std::uint8_t*>(b.data()), 1000, 3, "cap",
                          kCapture0);
            }).find("packet 3: data packet of 1000 bytes"),
            std::string::npos);
}

// --- The pcap reader: ports, counts, and capture-level errors -----------------------------------

TEST(VelodynePcapReader, ReadsDataPortCountsPositionAndOthers) {
  pcap_test::Pcap cap;
  cap.src_port = 2368;
  const Spec s = vlp16Spec();
  for (int p = 0; p < 76; p++) {
    cap.time_ns = captureTime(s, p);
    cap.udp(2368, packet(s, p), p == 3);  // one datagram in two IPv4 fragments
    if (p % 10 == 0) cap.udp(8308, std::string(512, '\x01'));
  }
  cap.udp(7502, std::string(100, '\0'));
  cap.record(pcap_test::Pcap::ethernet(std::string(28, '\0'), 0x0806));  // ARP
  const std::string path = cap.save(tempPath("vlp16.pcap"));
  VelodynePcapReader reader(path, {});
  VelodyneScan scan;
  std::vector<VelodyneScan> scans;
  while (reader.next(scan)) scans.push_back(scan);
  std::filesystem::remove(path);
  ASSERT_EQ(scans.size(), 1u);
  const auto& st = reader.stats();
  EXPECT_EQ(st.data_packets, 76u);
  EXPECT_EQ(st.position_packets, 8u);
  EXPECT_EQ(st.other_packets, 2u);
  EXPECT_EQ(st.fragments_reassembled, 1u);
  EXPECT_EQ(st.frames, 1u);
  EXPECT_EQ(st.partial_frames_skipped, 1u);
  EXPECT_EQ(st.points, 1800u * 16 - 150);
  EXPECT_EQ(st.no_returns, 150u);
  EXPECT_EQ(scans[0].capture_time_ns, kCapture0);
}

TEST(VelodynePcapReader, CaptureLevelErrors) {
  // An Ouster-like capture: UDP, but nothing on 2368.
  pcap_test::Pcap ouster;
  for (int i = 0; i < 3; i++) ouster.udp(7502, std::string(200, '\0'));
  ouster.udp(7503, std::string(48, '\0'));
  const std::string path = ouster.save(tempPath("ouster.pcap"));
  EXPECT_EQ(
      errorOf([&] {
        VelodynePcapReader r(path, {});
        VelodyneScan s;
        r.next(s);
      }),
      path + ": no Velodyne data packets (UDP port 2368); UDP ports seen: 7502 (3), 7503 (1)");
  // A data packet cut short by the snap length.
  pcap_test::Pcap cut;
  cut.udp(2368, packet(vlp16Spec(), 0), false, 14 + 20 + 8 + 600);
  const std::string cut_path = cut.save(tempPath("cut.pcap"));
  EXPECT_NE(errorOf([&] {
              VelodynePcapReader r(cut_path, {});
              VelodyneScan s;
              r.next(s);
            }).find("packet 1: captured 600 of 1206 bytes of a data packet (snap length"),
            std::string::npos);
  // Not a pcap at all.
  const std::string text = tempPath("text.pcap");
  std::ofstream(text) << "not a capture\n";
  EXPECT_NE(errorOf([&] { VelodynePcapReader r(text, {}); }).find("not a readable pcap"),
            std::string::npos);
  for (const auto& p : {path, cut_path, text}) std::filesystem::remove(p);
}

}  // namespace
