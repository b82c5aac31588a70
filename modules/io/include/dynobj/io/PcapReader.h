// SPDX-License-Identifier: BSD-3-Clause
// UDP datagrams out of a pcap / pcapng capture (libpcap): link layer (Ethernet with optional
// VLAN tags, Linux cooked SLL / SLL2, raw IP) -> IPv4 with fragment reassembly -> UDP payload,
// destination port and capture time. Knows nothing about the payloads.
//
// What is an error (FormatError "<path>: record N: ...", N = 1-based record number, as
// Wireshark counts): a file that is not a pcap, an unsupported link type, a corrupt record
// header mid-file, an IPv4 / UDP header whose lengths are impossible in a complete record.
// What is counted and skipped: records that are not IPv4/UDP (ARP, IPv6, TCP, ...); a record
// cut off by the end of the file (a capture that was stopped while writing: reading ends
// there); fragments whose datagram never completes; an unfragmented IPv4 packet whose header
// announces more bytes than its complete record holds (early VLP-16 firmware: 1234 in its
// position packets), which is read with the record's length. A datagram captured shorter than its
// headers announce (snap length) is returned with `truncated` set: the caller decides.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

struct pcap;  // libpcap's pcap_t, kept out of this header

namespace dynobj::io {

class PcapReader {
 public:
  struct Datagram {
    std::vector<std::uint8_t> payload;  ///< UDP payload (what was captured of it)
    std::uint16_t src_port = 0, dst_port = 0;
    std::int64_t time_ns = 0;   ///< capture time of the record that completed it [ns]
    std::size_t record = 0;     ///< 1-based record number that completed it
    std::size_t announced = 0;  ///< payload size the UDP header announces
    bool truncated = false;     ///< payload.size() < announced (snap length)
    int fragments = 1;          ///< IPv4 fragments it was reassembled from
  };
  struct Stats {
    std::size_t records = 0;               ///< pcap records read
    std::size_t datagrams = 0;             ///< UDP datagrams returned
    std::size_t not_udp = 0;               ///< records that are not IPv4/UDP
    std::size_t fragments = 0;             ///< records holding an IPv4 fragment
    std::size_t reassembled = 0;           ///< datagrams built from several fragments
    std::size_t fragments_dropped = 0;     ///< fragments of datagrams that never completed
    std::size_t truncated_at_end = 0;      ///< 1 if the file ends inside a record
    std::size_t ip_length_overstated = 0;  ///< complete records read with their own length
  };

  /// Opens the capture; FormatError if it cannot be read or is not a pcap / pcapng file.
  explicit PcapReader(const std::string& path);
  ~PcapReader();
  PcapReader(const PcapReader&) = delete;
  PcapReader& operator=(const PcapReader&) = delete;

  /// Next UDP datagram; false at the end of the capture.
  bool next(Datagram& out);
  const Stats& stats() const { return stats_; }
  const std::string& path() const { return path_; }

 private:
  struct Piece {
    std::size_t offset = 0, length = 0;  ///< extent in the IP payload (announced)
    std::vector<std::uint8_t> data;      ///< captured bytes (may be shorter)
  };
  struct Pending {
    std::vector<Piece> pieces;
    std::size_t total = 0;  ///< IP payload size, known once the last fragment arrived
    std::size_t order = 0;  ///< arrival order of its first fragment (for eviction)
  };
  using FragmentKey = std::tuple<std::uint32_t, std::uint32_t, std::uint16_t>;

  bool handleRecord(const std::uint8_t* data, std::size_t caplen, std::size_t wirelen,
                    std::int64_t time_ns, Datagram& out);
  bool addFragment(const FragmentKey& key, Piece piece, bool last, Datagram& out);
  bool emitUdp(const std::uint8_t* ip_payload, std::size_t captured, std::size_t announced,
               Datagram& out);
  [[noreturn]] void fail(const std::string& problem) const;

  std::string path_;
  ::pcap* pcap_ = nullptr;
  int link_type_ = 0;
  Stats stats_;
  std::map<FragmentKey, Pending> pending_;
  std::size_t arrivals_ = 0;
  bool done_ = false;
};

}  // namespace dynobj::io
