// SPDX-License-Identifier: BSD-3-Clause
// pcap records -> UDP datagrams (link layer, IPv4, fragment reassembly); rules in the header.
#include "dynobj/io/PcapReader.h"

#include <pcap/pcap.h>

#include <algorithm>

#include "dynobj/io/FormatError.h"

namespace dynobj::io {
namespace {

constexpr std::size_t kMaxPendingDatagrams = 64;
constexpr std::size_t kMaxFragmentsPerDatagram = 256;

std::uint16_t be16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
}
std::uint32_t be32(const std::uint8_t* p) {
  return (std::uint32_t{p[0]} << 24) | (std::uint32_t{p[1]} << 16) | (std::uint32_t{p[2]} << 8) |
         std::uint32_t{p[3]};
}

// Length of the prefix [0, x) covered by the given (offset, length) extents.
std::size_t coveredPrefix(std::vector<std::pair<std::size_t, std::size_t>> ext) {
  std::sort(ext.begin(), ext.end());
  std::size_t covered = 0;
  for (const auto& [off, len] : ext) {
    if (off > covered) break;
    covered = std::max(covered, off + len);
  }
  return covered;
}

}  // namespace

PcapReader::PcapReader(const std::string& path) : path_(path) {
  char err[PCAP_ERRBUF_SIZE] = {};
  pcap_ = pcap_open_offline_with_tstamp_precision(path.c_str(), PCAP_TSTAMP_PRECISION_NANO, err);
  if (!pcap_)
    throwFormatError(path, std::string("not a readable pcap capture (libpcap: ") + err + ")");
  link_type_ = pcap_datalink(pcap_);
  if (link_type_ != DLT_EN10MB && link_type_ != DLT_LINUX_SLL && link_type_ != DLT_LINUX_SLL2 &&
      link_type_ != DLT_RAW && link_type_ != DLT_IPV4) {
    pcap_close(pcap_);
    pcap_ = nullptr;
    throwFormatError(path, "unsupported link type " + std::to_string(link_type_) +
                               " (supported: Ethernet, Linux cooked SLL/SLL2, raw IPv4)");
  }
}

PcapReader::~PcapReader() {
  if (pcap_) pcap_close(pcap_);
}

void PcapReader::fail(const std::string& problem) const {
  throwFormatError(path_, "record " + std::to_string(stats_.records) + ": " + problem);
}

bool PcapReader::next(Datagram& out) {
  while (!done_) {
    pcap_pkthdr* hdr = nullptr;
    const u_char* data = nullptr;
    const int rc = pcap_next_ex(pcap_, &hdr, &data);
    if (rc == 1) {
      stats_.records++;
      const std::int64_t t = std::int64_t{hdr->ts.tv_sec} * 1000000000LL + hdr->ts.tv_usec;
      if (handleRecord(data, hdr->caplen, hdr->len, t, out)) {
        stats_.datagrams++;
        return true;
      }
      continue;
    }
    done_ = true;
    if (rc == -1) {
      const std::string msg = pcap_geterr(pcap_);
      if (msg.find("truncated") == std::string::npos) {
        stats_.records++;
        fail(msg);
      }
      stats_.truncated_at_end = 1;
    }
  }
  for (const auto& kv : pending_) stats_.fragments_dropped += kv.second.pieces.size();
  pending_.clear();
  return false;
}

bool PcapReader::handleRecord(const std::uint8_t* p, std::size_t n, std::size_t wirelen,
                              std::int64_t time_ns, Datagram& out) {
  const auto skip = [this] {
    stats_.not_udp++;
    return false;
  };
  // Link layer -> offset of the IPv4 header.
  std::size_t off = 0;
  std::uint16_t proto = 0;
  if (link_type_ == DLT_EN10MB) {
    if (n < 14) return skip();
    proto = be16(p + 12);
    off = 14;
    while ((proto == 0x8100 || proto == 0x88A8) && n >= off + 4) {  // VLAN tags
      proto = be16(p + off + 2);
      off += 4;
    }
  } else if (link_type_ == DLT_LINUX_SLL) {
    if (n < 16) return skip();
    proto = be16(p + 14);
    off = 16;
  } else if (link_type_ == DLT_LINUX_SLL2) {
    if (n < 20) return skip();
    proto = be16(p);
    off = 20;
  } else {
    proto = (n > 0 && (p[0] >> 4) == 4) ? 0x0800 : 0;
  }
  if (proto != 0x0800) return skip();

  const std::uint8_t* ip = p + off;
  const std::size_t avail = n - off;
  if (avail < 20) fail("IPv4 header cut short (" + std::to_string(avail) + " bytes)");
  if ((ip[0] >> 4) != 4) fail("IPv4 ethertype but IP version " + std::to_string(ip[0] >> 4));
  const std::size_t ihl = std::size_t{ip[0] & 15u} * 4;
  const std::size_t total = be16(ip + 2);
  if (ihl < 20 || ihl > avail || total < ihl)
    fail("bad IPv4 lengths (header " + std::to_string(ihl) + ", total " + std::to_string(total) +
         ")");
  if (ip[9] != 17) return skip();
  const std::uint16_t flags = be16(ip + 6);
  const bool more = (flags & 0x2000) != 0;
  const std::size_t frag_off = std::size_t{flags & 0x1FFFu} * 8;
  std::size_t total_used = total;
  if (total > avail && n >= wirelen) {
    if (more || frag_off != 0)
      fail("IPv4 total length " + std::to_string(total) + " but only " + std::to_string(avail) +
           " bytes in the record");
    // A complete record whose IPv4 header overstates its length (early VLP-16 firmware writes
    // 1234 into its 554-byte position packets): the record's length is the packet's.
    stats_.ip_length_overstated++;
    total_used = avail;
  }
  const std::size_t captured = std::min(total_used, avail) - ihl;
  const std::size_t announced = total_used - ihl;

  out.record = stats_.records;
  out.time_ns = time_ns;
  out.fragments = 1;
  if (!more && frag_off == 0) return emitUdp(ip + ihl, captured, announced, out);

  stats_.fragments++;
  if (frag_off + announced > 65535) fail("IPv4 fragment ends beyond 64 KiB");
  Piece piece;
  piece.offset = frag_off;
  piece.length = announced;
  piece.data.assign(ip + ihl, ip + ihl + captured);
  return addFragment(FragmentKey{be32(ip + 12), be32(ip + 16), be16(ip + 4)}, std::move(piece),
                     !more, out);
}

bool PcapReader::addFragment(const FragmentKey& key, Piece piece, bool last, Datagram& out) {
  if (!pending_.count(key) && pending_.size() >= kMaxPendingDatagrams) {
    auto oldest = std::min_element(
        pending_.begin(), pending_.end(),
        [](const auto& a, const auto& b) { return a.second.order < b.second.order; });
    stats_.fragments_dropped += oldest->second.pieces.size();
    pending_.erase(oldest);
  }
  auto [it, created] = pending_.try_emplace(key);
  Pending& g = it->second;
  if (created) g.order = arrivals_++;
  if (last) {
    if (g.total != 0 && g.total != piece.offset + piece.length)
      fail("two last fragments of one datagram disagree on its length");
    g.total = piece.offset + piece.length;
  }
  g.pieces.push_back(std::move(piece));
  if (g.pieces.size() > kMaxFragmentsPerDatagram) fail("more than 256 fragments in one datagram");
  if (g.total == 0) return false;

  std::vector<std::pair<std::size_t, std::size_t>> announced, captured;
  for (const auto& pc : g.pieces) {
    announced.emplace_back(pc.offset, pc.length);
    captured.emplace_back(pc.offset, pc.data.size());
  }
  if (coveredPrefix(announced) < g.total) return false;

  std::vector<std::uint8_t> buf(g.total, 0);
  for (const auto& pc : g.pieces) {
    if (pc.offset >= g.total) continue;
    const std::size_t len = std::min(pc.data.size(), g.total - pc.offset);
    std::copy_n(pc.data.begin(), len, buf.begin() + static_cast<std::ptrdiff_t>(pc.offset));
  }
  const std::size_t have = std::min(coveredPrefix(captured), g.total);
  const std::size_t total = g.total;
  out.fragments = static_cast<int>(g.pieces.size());
  pending_.erase(it);
  stats_.reassembled++;
  return emitUdp(buf.data(), have, total, out);
}

bool PcapReader::emitUdp(const std::uint8_t* u, std::size_t captured, std::size_t announced,
                         Datagram& out) {
  if (captured < 8) fail("UDP header not captured");
  const std::size_t ulen = be16(u + 4);
  if (ulen < 8 || ulen > announced)
    fail("UDP length " + std::to_string(ulen) + " does not fit the IPv4 payload of " +
         std::to_string(announced) + " bytes");
  out.src_port = be16(u);
  out.dst_port = be16(u + 2);
  out.announced = ulen - 8;
  const std::size_t have = std::min(captured, ulen) - 8;
  out.payload.assign(u + 8, u + 8 + have);
  out.truncated = have < out.announced;
  return true;
}

}  // namespace dynobj::io
