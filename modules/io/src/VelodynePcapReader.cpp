// SPDX-License-Identifier: BSD-3-Clause
// Velodyne pcap capture -> sweeps (rules in the header).
#include "dynobj/io/VelodynePcapReader.h"

#include "dynobj/io/FormatError.h"

namespace dynobj::io {

VelodynePcapReader::VelodynePcapReader(const std::string& pcap_path, Options options)
    : pcap_(pcap_path), options_(std::move(options)), decoder_(options_.decoder) {}

bool VelodynePcapReader::next(VelodyneScan& scan) {
  PcapReader::Datagram d;
  while (true) {
    if (decoder_.popFrame(scan)) {
      stats_.frames++;
      stats_.points += scan.cloud.size();
      stats_.no_returns += scan.no_return;
      updateStats();
      return true;
    }
    if (ended_) {
      updateStats();
      return false;
    }
    if (!pcap_.next(d)) {
      ended_ = true;
      updateStats();
      if (stats_.data_packets == 0) {
        std::string ports;
        for (const auto& [port, count] : other_ports_)
          ports += (ports.empty() ? "" : ", ") + std::to_string(port) + " (" +
                   std::to_string(count) + ")";
        throwFormatError(
            pcap_.path(),
            "no Velodyne data packets (UDP port " + std::to_string(options_.data_port) + "); " +
                (ports.empty() ? "no UDP traffic at all" : "UDP ports seen: " + ports));
      }
      decoder_.flush(pcap_.path());
      continue;
    }
    if (d.fragments > 1) stats_.fragments_reassembled++;
    if (d.dst_port == options_.position_port) {
      stats_.position_packets++;
      continue;
    }
    if (d.dst_port != options_.data_port) {
      other_udp_++;
      other_ports_[d.dst_port]++;
      continue;
    }
    stats_.data_packets++;
    if (d.truncated)
      throwFormatError(pcap_.path(), "packet " + std::to_string(d.record) + ": captured " +
                                         std::to_string(d.payload.size()) + " of " +
                                         std::to_string(d.announced) +
                                         " bytes of a data packet (snap length too small)");
    decoder_.addPacket(d.payload.data(), d.payload.size(), d.record, pcap_.path(), d.time_ns);
  }
}

void VelodynePcapReader::updateStats() {
  const PcapReader::Stats& p = pcap_.stats();
  stats_.packets = p.records;
  stats_.other_packets = other_udp_ + p.not_udp;
  stats_.bad_packets = p.truncated_at_end + p.fragments_dropped;
  stats_.partial_frames_skipped = decoder_.partialFramesSkipped();
  stats_.second_returns_dropped = decoder_.secondReturnsDropped();
  stats_.clock_jumps = decoder_.clockJumps();
}

}  // namespace dynobj::io
