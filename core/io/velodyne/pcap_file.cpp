#include "io/velodyne/pcap_file.h"

#include <pcap/pcap.h>

#include <cstdio>
#include <cstring>
#include <filesystem>

#include "common/error.h"

namespace storey::velodyne {
namespace {

constexpr int kLinkNull = 0;         // BSD loopback
constexpr int kLinkEthernet = 1;
constexpr int kLinkRaw = 101;
constexpr int kLinkRawAlt1 = 12;
constexpr int kLinkRawAlt2 = 14;
constexpr int kLinkLinuxSll = 113;
constexpr int kLinkLinuxSll2 = 276;
constexpr int kLinkIpv4 = 228;
constexpr int kLinkIpv6 = 229;

std::uint16_t be16(const std::uint8_t* p) { return static_cast<std::uint16_t>((p[0] << 8) | p[1]); }

pcap_t* handleOf(void* h) { return static_cast<pcap_t*>(h); }

}  // namespace

bool isPcapMagic(const std::string& head) {
  if (head.size() < 4) return false;
  const unsigned char* m = reinterpret_cast<const unsigned char*>(head.data());
  const std::uint32_t le = m[0] | (m[1] << 8) | (m[2] << 16) | (static_cast<std::uint32_t>(m[3]) << 24);
  const std::uint32_t be = (static_cast<std::uint32_t>(m[0]) << 24) | (m[1] << 16) | (m[2] << 8) | m[3];
  for (std::uint32_t magic : {0xA1B2C3D4u, 0xA1B23C4Du}) {
    if (le == magic || be == magic) return true;
  }
  return le == 0x0A0D0D0Au;  // pcapng section header block
}

PcapFile::PcapFile(const std::string& path) : path_(path) {
  std::error_code ec;
  file_size_ = std::filesystem::file_size(path, ec);
  char errbuf[PCAP_ERRBUF_SIZE] = {};
  pcap_t* p = pcap_open_offline_with_tstamp_precision(path.c_str(), PCAP_TSTAMP_PRECISION_NANO,
                                                      errbuf);
  if (p == nullptr) throw Error(path + ": cannot read the capture: " + errbuf);
  handle_ = p;
  link_type_ = pcap_datalink(p);
  nano_ = pcap_get_tstamp_precision(p) == PCAP_TSTAMP_PRECISION_NANO;
}

PcapFile::~PcapFile() {
  if (handle_ != nullptr) pcap_close(handleOf(handle_));
}

std::int64_t PcapFile::bytesRead() const {
  FILE* f = pcap_file(handleOf(handle_));
  return f != nullptr ? static_cast<std::int64_t>(std::ftell(f)) : -1;
}

std::string PcapFile::linkTypeName() const {
  const char* name = pcap_datalink_val_to_name(link_type_);
  return name != nullptr ? name : "DLT " + std::to_string(link_type_);
}

bool PcapFile::next(UdpDatagram& out) {
  if (!cut_message_.empty()) return false;
  for (;;) {
    const std::int64_t offset = bytesRead();
    pcap_pkthdr* header = nullptr;
    const u_char* data = nullptr;
    const int rc = pcap_next_ex(handleOf(handle_), &header, &data);
    if (rc == PCAP_ERROR_BREAK) return false;  // end of file
    if (rc != 1) {
      cut_message_ = pcap_geterr(handleOf(handle_));
      cut_message_ += " (record " + std::to_string(records_) + ", byte offset " +
                      std::to_string(offset) + ")";
      ++skipped_[kSkipCutRecord];
      return false;
    }
    const std::int64_t index = records_++;
    const std::int64_t seconds = header->ts.tv_sec;
    const std::int64_t fraction = header->ts.tv_usec;  // ns with nano precision
    out.record_ns = seconds * 1'000'000'000 + (nano_ ? fraction : fraction * 1000);
    out.record_index = index;
    out.file_offset = offset;
    if (parse(data, header->caplen, header->len, out)) return true;
  }
}

bool PcapFile::parse(const std::uint8_t* p, std::size_t caplen, std::size_t len, UdpDatagram& out) {
  std::size_t at = 0;
  std::uint16_t ethertype = 0;
  auto need = [&](std::size_t bytes) {
    if (caplen >= at + bytes) return true;
    ++skipped_[caplen < len ? kSkipTruncated : kSkipMalformed];
    return false;
  };
  switch (link_type_) {
    case kLinkEthernet:
      if (!need(14)) return false;
      ethertype = be16(p + 12);
      at = 14;
      while (ethertype == 0x8100 || ethertype == 0x88A8) {  // VLAN tags
        if (!need(4)) return false;
        ethertype = be16(p + at + 2);
        at += 4;
      }
      break;
    case kLinkLinuxSll:
      if (!need(16)) return false;
      ethertype = be16(p + 14);
      at = 16;
      break;
    case kLinkLinuxSll2:
      if (!need(20)) return false;
      ethertype = be16(p);
      at = 20;
      break;
    case kLinkNull: {
      if (!need(4)) return false;
      const std::uint32_t family = p[0] | (p[1] << 8) | (p[2] << 16) | (static_cast<std::uint32_t>(p[3]) << 24);
      ethertype = family == 2 ? 0x0800 : 0x86DD;
      at = 4;
      break;
    }
    case kLinkRaw: case kLinkRawAlt1: case kLinkRawAlt2: case kLinkIpv4: case kLinkIpv6:
      if (!need(1)) return false;
      ethertype = (p[0] >> 4) == 6 ? 0x86DD : 0x0800;
      break;
    default:
      ++skipped_[kSkipNotIp];
      return false;
  }
  if (ethertype == 0x0800) {
    if (!need(20)) return false;
    if ((p[at] >> 4) != 4) { ++skipped_[kSkipMalformed]; return false; }
    const std::size_t ihl = static_cast<std::size_t>(p[at] & 0x0F) * 4;
    if (ihl < 20 || !need(ihl)) { if (ihl < 20) ++skipped_[kSkipMalformed]; return false; }
    const std::uint16_t flags_fragment = be16(p + at + 6);
    if ((flags_fragment & 0x3FFF) != 0) { ++skipped_[kSkipFragment]; return false; }
    if (p[at + 9] != 17) { ++skipped_[kSkipNotUdp]; return false; }
    at += ihl;
  } else if (ethertype == 0x86DD) {
    if (!need(40)) return false;
    if (p[at + 6] != 17) { ++skipped_[kSkipNotUdp]; return false; }  // extension headers: not UDP data
    at += 40;
  } else {
    ++skipped_[kSkipNotIp];
    return false;
  }
  if (!need(8)) return false;
  out.src_port = be16(p + at);
  out.dst_port = be16(p + at + 2);
  const std::size_t udp_length = be16(p + at + 4);
  if (udp_length < 8) { ++skipped_[kSkipMalformed]; return false; }
  at += 8;
  const std::size_t payload = udp_length - 8;
  out.payload = p + at;
  out.size = std::min(payload, caplen - at);  // a truncated datagram is reported by its size
  if (out.size < payload && caplen >= len) { ++skipped_[kSkipMalformed]; return false; }
  return true;
}

}  // namespace storey::velodyne
