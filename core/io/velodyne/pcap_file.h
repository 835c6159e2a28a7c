#pragma once
/// Sequential reading of the UDP datagrams of a capture file (pcap or pcapng,
/// read with libpcap): link layer (Ethernet with VLAN tags, Linux cooked v1/v2,
/// raw IP, BSD loopback) -> IPv4/IPv6 -> UDP. Everything else is skipped and
/// counted by reason. libpcap stays inside pcap_file.cpp.
#include <cstdint>
#include <map>
#include <memory>
#include <string>

namespace storey::velodyne {

/// Keys of the skip counts (records of the capture).
inline constexpr const char* kSkipNotIp = "pcap_record_not_ip";
inline constexpr const char* kSkipNotUdp = "pcap_record_not_udp";
inline constexpr const char* kSkipFragment = "pcap_record_ip_fragment";
inline constexpr const char* kSkipTruncated = "pcap_record_truncated";
inline constexpr const char* kSkipMalformed = "pcap_record_malformed";
inline constexpr const char* kSkipCutRecord = "pcap_file_cut_in_record";

struct UdpDatagram {
  std::int64_t record_ns = 0;  ///< capture time of the record (host clock) [ns since 1970]
  std::uint16_t src_port = 0;
  std::uint16_t dst_port = 0;
  const std::uint8_t* payload = nullptr;  ///< valid until the next call of next()
  std::size_t size = 0;                   ///< payload bytes present
  std::int64_t record_index = 0;          ///< 0-based record number in the file
  std::int64_t file_offset = 0;           ///< byte offset of the record header (pcap), or -1
};

class PcapFile {
 public:
  /// Opens `path`; throws storey::Error naming the file when libpcap cannot read it.
  explicit PcapFile(const std::string& path);
  ~PcapFile();
  PcapFile(const PcapFile&) = delete;
  PcapFile& operator=(const PcapFile&) = delete;

  /// Next UDP datagram; false at the end of the file (or where it is cut, see cutAt()).
  bool next(UdpDatagram& datagram);

  const std::string& path() const { return path_; }
  std::uint64_t fileSize() const { return file_size_; }
  std::int64_t records() const { return records_; }        ///< records read so far
  std::int64_t bytesRead() const;                          ///< position in the file
  int linkType() const { return link_type_; }
  std::string linkTypeName() const;
  /// Skipped records by reason (kSkip* keys).
  const std::map<std::string, std::int64_t>& skipped() const { return skipped_; }
  /// Non-empty when reading stopped at a damaged or cut record: libpcap's message.
  const std::string& cutAt() const { return cut_message_; }

 private:
  bool parse(const std::uint8_t* data, std::size_t caplen, std::size_t len, UdpDatagram& out);

  std::string path_;
  void* handle_ = nullptr;  ///< pcap_t*
  int link_type_ = 0;
  bool nano_ = false;
  std::uint64_t file_size_ = 0;
  std::int64_t records_ = 0;
  std::map<std::string, std::int64_t> skipped_;
  std::string cut_message_;
};

/// True when `head` (the first bytes of a file) starts with a pcap or pcapng magic number.
bool isPcapMagic(const std::string& head);

}  // namespace storey::velodyne
