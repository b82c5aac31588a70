// SPDX-License-Identifier: BSD-3-Clause
// Ouster pcap capture -> frames (rules in the header).
#include "dynobj/io/OusterPcapReader.h"

#include "dynobj/io/FormatError.h"

namespace dynobj::io {

OusterPcapReader::OusterPcapReader(const std::string& pcap_path, const OusterMetadata& meta)
    : pcap_(pcap_path), decoder_(meta) {}

bool OusterPcapReader::next(OusterScan& scan) {
  PcapReader::Datagram d;
  while (true) {
    if (decoder_.popFrame(scan)) {
      stats_.frames++;
      updateStats();
      return true;
    }
    if (ended_) return false;
    if (!pcap_.next(d)) {
      ended_ = true;
      decoder_.flush();
      updateStats();
      if (stats_.lidar_packets == 0 && !other_ports_.empty()) {
        std::string ports;
        for (const auto& [port, count] : other_ports_)
          ports += (ports.empty() ? "" : ", ") + std::to_string(port) + " (" +
                   std::to_string(count) + ")";
        throwFormatError(pcap_.path(), "no UDP packets on the lidar port " +
                                           std::to_string(metadata().udp_port_lidar) +
                                           "; ports seen: " + ports);
      }
      continue;
    }
    if (d.fragments > 1) stats_.fragments_reassembled++;
    if (d.dst_port != metadata().udp_port_lidar) {
      other_udp_++;
      other_ports_[d.dst_port]++;
      continue;
    }
    stats_.lidar_packets++;
    if (d.truncated)
      throwFormatError(pcap_.path(), "packet " + std::to_string(d.record) + ": captured " +
                                         std::to_string(d.payload.size()) + " of " +
                                         std::to_string(d.announced) +
                                         " bytes of a lidar packet (snap length too small)");
    decoder_.addPacket(d.payload.data(), d.payload.size(), d.record, pcap_.path(), d.time_ns);
  }
}

void OusterPcapReader::updateStats() {
  const PcapReader::Stats& p = pcap_.stats();
  stats_.packets = p.records;
  stats_.other_packets = other_udp_ + p.not_udp;
  stats_.bad_packets = p.truncated_at_end + p.fragments_dropped;
  stats_.partial_frames_skipped = decoder_.partialFramesSkipped();
  stats_.init_id_mismatches = decoder_.initIdMismatches();
}

}  // namespace dynobj::io
