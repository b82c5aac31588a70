// SPDX-License-Identifier: BSD-3-Clause
// Velodyne reader on the real captures in ../shared/realdata/velodyne (Kitware VeloView test
// data, Apache-2.0, not part of this project): packet counts, sweeps, rows, points against the
// packet count and the beam table. Skipped where that folder is absent. Prints the figures.
#include <dynobj/io/FormatError.h>
#include <dynobj/io/PcapReader.h>
#include <dynobj/io/VelodynePcapReader.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

using namespace dynobj::io;

namespace {

const std::string kDir = DYNOBJ_SOURCE_DIR "/../shared/realdata/velodyne/";

#define SKIP_WITHOUT_REAL_DATA()            \
  if (!std::filesystem::is_directory(kDir)) \
  GTEST_SKIP() << "../shared/realdata/velodyne not found: real-capture tests skipped"

// Azimuth wrap-arounds in the raw data packets (block azimuth falling by more than 180 deg),
// counted here without the decoder: the capture holds wraps + 1 sweeps, full or partial.
std::size_t rawWraps(const std::string& file) {
  PcapReader pcap(kDir + file);
  PcapReader::Datagram d;
  int last = -1;
  std::size_t wraps = 0;
  while (pcap.next(d)) {
    if (d.dst_port != 2368) continue;
    for (int b = 0; b < 12; b++) {
      const int az = (d.payload[100 * b + 2] | (d.payload[100 * b + 3] << 8)) % 36000;
      if (last >= 0 && az < last - 18000) wraps++;
      last = az;
    }
  }
  return wraps;
}

struct Decoded {
  std::vector<VelodyneScan> scans;
  VelodynePcapReader::Stats stats;
  int cols = 0;
  double frequency = 0;
  std::string model;
};

Decoded decode(const std::string& file, VelodynePcapReader::Options o = {}) {
  VelodynePcapReader reader(kDir + file, o);
  Decoded d;
  VelodyneScan s;
  while (reader.next(s)) d.scans.push_back(s);
  d.stats = reader.stats();
  d.cols = reader.decoder().cols();
  d.frequency = reader.decoder().frequencyHz();
  d.model = reader.decoder().sensor().name;
  return d;
}

// Checks every sweep against the packets: each firing gives one point per laser with a return,
// at the beam table's elevation; rows / columns inside the image; time within the sweep.
void checkSweeps(const Decoded& d, const VelodyneSensor& sensor, int firings_per_packet) {
  // One column per firing: columns x firing period = one turn.
  EXPECT_NEAR(d.cols * sensor.firing_period_us * 1e-6 * d.frequency, 1.0, 0.002);
  std::size_t firings = 0, points = 0;
  for (std::size_t f = 0; f < d.scans.size(); f++) {
    const VelodyneScan& s = d.scans[f];
    EXPECT_EQ(s.cloud.size() + s.no_return,
              static_cast<std::size_t>(s.firings) * static_cast<std::size_t>(sensor.lasers))
        << "sweep " << f;
    EXPECT_GE(s.azimuth_span_deg, 180.0);
    EXPECT_LT(s.azimuth_span_deg, 361.0);  // a VLP-16's second firing may pass 360
    firings += static_cast<std::size_t>(s.firings);
    points += s.cloud.size();
    for (std::size_t i = 0; i < s.cloud.size(); i++) {
      const double r = std::hypot(s.cloud.x[i], s.cloud.y[i], s.cloud.z[i]);
      const double e = std::asin(s.cloud.z[i] / r) * 180 / M_PI;
      ASSERT_NEAR(e, sensor.elevation_deg[s.cloud.ring[i]], 1e-3) << "sweep " << f << " " << i;
      ASSERT_LT(s.cloud.row[i], sensor.lasers);
      ASSERT_LT(s.cloud.col[i], d.cols);
      ASSERT_GE(s.time_ns[i], 0);
      ASSERT_LT(s.time_ns[i], 1e9 / d.frequency * 1.01);
    }
  }
  // The sweeps hold the firings of every data packet but those of the partial first and last.
  const std::size_t all = d.stats.data_packets * static_cast<std::size_t>(firings_per_packet);
  EXPECT_LE(firings, all);
  EXPECT_GE(firings + 2 * static_cast<std::size_t>(d.cols), all);
  EXPECT_EQ(points, d.stats.points);
}

TEST(VelodyneReal, MontereyHdl32e) {
  SKIP_WITHOUT_REAL_DATA();
  const Decoded d = decode("monterey-hdl32-first-100-packets.pcap");
  const auto& st = d.stats;
  std::printf(
      "HDL-32E Monterey: %zu data + %zu position packets -> %zu sweeps of 32 x %d at "
      "%.2f Hz, %zu points (%zu without return), %zu partial sweeps\n",
      st.data_packets, st.position_packets, st.frames, d.cols, d.frequency, st.points,
      st.no_returns, st.partial_frames_skipped);
  EXPECT_EQ(d.model, "HDL-32E");
  EXPECT_EQ(st.data_packets, 2702u);
  EXPECT_EQ(st.position_packets, 299u);
  EXPECT_EQ(st.other_packets, 0u);
  // 1.49 s at ~11.7 Hz: 17.5 turns; every segment between two wraps is a sweep unless it covers
  // less than 180 deg (at most the first and the last).
  EXPECT_EQ(st.frames + st.partial_frames_skipped,
            rawWraps("monterey-hdl32-first-100-packets.pcap") + 1);
  EXPECT_LE(st.partial_frames_skipped, 2u);
  EXPECT_GE(st.frames, 16u);
  // 0.195 deg between firings of 46.08 us: ~1850 firings per turn, ~11.7 Hz.
  EXPECT_NEAR(d.cols, 1850, 15);
  EXPECT_NEAR(d.frequency, 11.7, 0.2);
  checkSweeps(d, VelodyneSensor::of(VelodyneModel::HDL32E), 12);
}

TEST(VelodyneReal, Vlp16FactoryByteIsRefusedThenGivenModelDecodes) {
  SKIP_WITHOUT_REAL_DATA();
  // This early VLP-16 firmware writes the HDL-32E product id: the packet period gives it away.
  try {
    decode("vlp16-test-90deg-1-50-frames.pcap");
    ADD_FAILURE() << "no error";
  } catch (const FormatError& e) {
    EXPECT_NE(std::string(e.what()).find("models that fit: VLP-16, Puck Hi-Res"), std::string::npos)
        << e.what();
  }
  VelodynePcapReader::Options o;
  o.decoder.model = VelodyneModel::VLP16;
  const Decoded d = decode("vlp16-test-90deg-1-50-frames.pcap", o);
  const auto& st = d.stats;
  std::printf(
      "VLP-16 90deg: %zu data + %zu position packets -> %zu sweeps of 16 x %d at "
      "%.2f Hz, %zu points (%zu without return), %zu partial sweeps\n",
      st.data_packets, st.position_packets, st.frames, d.cols, d.frequency, st.points,
      st.no_returns, st.partial_frames_skipped);
  EXPECT_EQ(st.data_packets, 1902u);
  EXPECT_EQ(st.position_packets, 367u);
  EXPECT_EQ(st.frames + st.partial_frames_skipped,
            rawWraps("vlp16-test-90deg-1-50-frames.pcap") + 1);
  EXPECT_LE(st.partial_frames_skipped, 2u);
  EXPECT_GE(st.frames, 49u);    // "1-50 frames" at 20 Hz
  EXPECT_NEAR(d.cols, 900, 6);  // ~0.4 deg per firing at ~20 Hz
  EXPECT_NEAR(d.frequency, 20.0, 0.3);
  checkSweeps(d, VelodyneSensor::of(VelodyneModel::VLP16), 24);
}

}  // namespace
