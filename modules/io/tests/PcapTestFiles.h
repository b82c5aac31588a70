// SPDX-License-Identifier: BSD-3-Clause
// Test helpers shared by the pcap reader tests (Ouster, Velodyne): little / big-endian byte
// writing, per-test temporary paths, and a pcap file written byte by byte (Ethernet / IPv4 /
// UDP, optionally one datagram in two IPv4 fragments, optionally cut short by the snap length).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>

namespace pcap_test {

inline void put(std::string& s, std::uint64_t v, int bytes, bool big_endian = false) {
  for (int i = 0; i < bytes; i++) {
    const int shift = 8 * (big_endian ? bytes - 1 - i : i);
    s.push_back(static_cast<char>((v >> shift) & 0xFF));
  }
}

// Per-test names: CTest runs the tests of a binary as parallel processes.
inline std::string tempPath(const std::string& prefix, const std::string& name) {
  const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
  return ::testing::TempDir() + prefix + "_" + test->test_suite_name() + "_" + test->name() + "_" +
         name;
}

struct Pcap {
  std::string bytes;
  std::uint16_t ip_id = 1;
  std::uint16_t src_port = 7502;
  std::int64_t time_ns = 1700000000LL * 1000000000LL;  ///< capture time of the next record
  Pcap() {
    put(bytes, 0xA1B2C3D4, 4), put(bytes, 2, 2), put(bytes, 4, 2), put(bytes, 0, 8);
    put(bytes, 65535, 4), put(bytes, 1, 4);  // snap length, Ethernet
  }
  void record(const std::string& frame, std::size_t captured = std::string::npos) {
    const std::size_t cap = std::min(captured, frame.size());
    put(bytes, static_cast<std::uint64_t>(time_ns / 1000000000), 4);
    put(bytes, static_cast<std::uint64_t>(time_ns % 1000000000 / 1000), 4);  // microseconds
    put(bytes, cap, 4), put(bytes, frame.size(), 4);
    bytes += frame.substr(0, cap);
  }
  static std::string ethernet(const std::string& payload, std::uint16_t type = 0x0800) {
    std::string s(12, '\x02');
    put(s, type, 2, true);
    return s + payload;
  }
  std::string ipv4(const std::string& payload, std::uint16_t flags_offset) const {
    std::string s;
    put(s, 0x45, 1), put(s, 0, 1), put(s, 20 + payload.size(), 2, true), put(s, ip_id, 2, true);
    put(s, flags_offset, 2, true), put(s, 64, 1), put(s, 17, 1), put(s, 0, 2);
    put(s, 0xC0A80101, 4, true), put(s, 0xC0A80102, 4, true);
    return s + payload;
  }
  // One UDP datagram; `fragmented`: two IPv4 fragments, the second one first.
  void udp(std::uint16_t port, const std::string& payload, bool fragmented = false,
           std::size_t captured = std::string::npos) {
    std::string u;
    put(u, src_port, 2, true), put(u, port, 2, true), put(u, 8 + payload.size(), 2, true);
    put(u, 0, 2);
    u += payload;
    if (fragmented) {
      record(ethernet(ipv4(u.substr(64), 64 / 8)));
      record(ethernet(ipv4(u.substr(0, 64), 0x2000)));  // more fragments
    } else {
      record(ethernet(ipv4(u, 0)), captured);
    }
    ip_id++;
  }
  std::string save(const std::string& path) const {
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
};

}  // namespace pcap_test
