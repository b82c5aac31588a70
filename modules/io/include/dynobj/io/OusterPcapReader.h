// SPDX-License-Identifier: BSD-3-Clause
// Frames of an Ouster pcap capture: PcapReader (UDP datagrams) + OusterDecoder (frames), with
// the counts a user needs to judge the capture.
//
// Per datagram: the metadata's lidar port -> decoded (errors: see OusterDecoder.h; a lidar
// datagram cut short by the capture's snap length is an error too, naming the packet); other
// ports (IMU on 7503, ...) and non-UDP records -> counted in other_packets. A capture with UDP
// traffic but nothing on the lidar port is an error naming the ports seen. A record cut off
// by the end of the file, and fragments that never complete, are counted in bad_packets.
#pragma once

#include <cstddef>
#include <map>
#include <string>

#include "dynobj/io/OusterDecoder.h"
#include "dynobj/io/OusterMetadata.h"
#include "dynobj/io/PcapReader.h"

namespace dynobj::io {

class OusterPcapReader {
 public:
  struct Stats {
    std::size_t packets = 0;                 ///< pcap records read
    std::size_t lidar_packets = 0;           ///< datagrams on the lidar port
    std::size_t other_packets = 0;           ///< other ports, non-UDP records
    std::size_t fragments_reassembled = 0;   ///< datagrams rebuilt from IPv4 fragments
    std::size_t bad_packets = 0;             ///< cut-off last record, incomplete fragments
    std::size_t frames = 0;                  ///< full frames returned by next()
    std::size_t partial_frames_skipped = 0;  ///< frames with < 50 % of the column window
    std::size_t init_id_mismatches = 0;      ///< packets of another sensor initialisation
  };

  /// Opens the capture; FormatError if it is unreadable or not a pcap / pcapng file.
  OusterPcapReader(const std::string& pcap_path, const OusterMetadata& meta);

  /// Next full frame; false at the end of the capture.
  bool next(OusterScan& scan);
  const Stats& stats() const { return stats_; }
  const OusterMetadata& metadata() const { return decoder_.metadata(); }

 private:
  void updateStats();

  PcapReader pcap_;
  OusterDecoder decoder_;
  Stats stats_;
  std::map<int, std::size_t> other_ports_;  ///< datagrams per destination port (not lidar)
  std::size_t other_udp_ = 0;
  bool ended_ = false;
};

}  // namespace dynobj::io
