// SPDX-License-Identifier: BSD-3-Clause
// Sweeps of a Velodyne pcap capture: PcapReader (UDP datagrams) + VelodyneDecoder (sweeps), with
// the counts a user needs to judge the capture.
//
// Per datagram: the data port (2368 unless told) -> decoded (errors: see VelodyneDecoder.h; a
// data packet cut short by the capture's snap length is an error too, naming the packet); the
// position port (8308) -> counted; other ports and non-UDP records -> counted in other_packets.
// A capture with UDP traffic but nothing on the data port is an error naming the ports seen. A
// record cut off by the end of the file, and fragments that never complete, are counted in
// bad_packets.
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include "dynobj/io/PcapReader.h"
#include "dynobj/io/VelodyneDecoder.h"

namespace dynobj::io {

class VelodynePcapReader {
 public:
  struct Options {
    VelodyneOptions decoder;
    int data_port = 2368;      ///< UDP destination port of the data packets
    int position_port = 8308;  ///< UDP destination port of the position (GPS / IMU) packets
  };
  struct Stats {
    std::size_t packets = 0;                 ///< pcap records read
    std::size_t data_packets = 0;            ///< datagrams on the data port
    std::size_t position_packets = 0;        ///< datagrams on the position port (not decoded)
    std::size_t other_packets = 0;           ///< other ports, non-UDP records
    std::size_t fragments_reassembled = 0;   ///< datagrams rebuilt from IPv4 fragments
    std::size_t bad_packets = 0;             ///< cut-off last record, incomplete fragments
    std::size_t frames = 0;                  ///< sweeps returned by next()
    std::size_t partial_frames_skipped = 0;  ///< sweeps covering < 180 deg
    std::size_t points = 0;                  ///< returns in the sweeps returned
    std::size_t no_returns = 0;              ///< firings without a return in those sweeps
    std::size_t second_returns_dropped = 0;  ///< dual-return mode: the returns not kept
    std::size_t clock_jumps = 0;             ///< sensor clock jumps (capture clock used)
  };

  /// Opens the capture; FormatError if it is unreadable or not a pcap / pcapng file.
  VelodynePcapReader(const std::string& pcap_path, Options options);

  /// Next sweep; false at the end of the capture.
  bool next(VelodyneScan& scan);
  const Stats& stats() const { return stats_; }
  const VelodyneDecoder& decoder() const { return decoder_; }

 private:
  void updateStats();

  PcapReader pcap_;
  Options options_;
  VelodyneDecoder decoder_;
  Stats stats_;
  std::map<int, std::size_t> other_ports_;  ///< datagrams per destination port (not data)
  std::size_t other_udp_ = 0;
  bool ended_ = false;
};

}  // namespace dynobj::io
