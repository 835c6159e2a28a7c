#pragma once
/// The two wire formats of ROS messages, read and written field by field:
///  - ROS 1 serialization: little-endian, packed (no alignment), strings as
///    uint32 length + bytes, time as uint32 sec + uint32 nsec;
///  - CDR as ROS 2 uses it (OMG CDR, XCDR version 1 "plain CDR"): a 4-byte
///    encapsulation header (0x00 0x00 big-endian, 0x00 0x01 little-endian, two
///    option bytes), then every primitive aligned to its own size (at most 8)
///    counted from the end of the header; strings as uint32 length including
///    the terminating NUL + bytes + NUL; time as int32 sec + uint32 nanosec.
/// Reads are bounds-checked: a message too short for a field throws
/// storey::Error naming the field and the byte offset (no file context).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace storey {

enum class WireFormat {
  kRos1,  ///< ROS 1 serialization ("ros1" message encoding in MCAP)
  kCdr,   ///< CDR with encapsulation header ("cdr" in rosbag2 and MCAP)
};

class WireReader {
 public:
  /// For kCdr reads and checks the encapsulation header (plain CDR, either
  /// byte order; XCDR2 and parameter lists are errors).
  WireReader(const std::uint8_t* data, std::size_t size, WireFormat format);

  std::uint8_t u8(const char* field);
  bool boolean(const char* field) { return u8(field) != 0; }
  std::uint16_t u16(const char* field);
  std::uint32_t u32(const char* field);
  std::int32_t i32(const char* field) { return static_cast<std::int32_t>(u32(field)); }
  double f64(const char* field);
  std::string string(const char* field);
  /// A sequence's element count (uint32), checked against the bytes left
  /// assuming each element needs at least `min_element_bytes`.
  std::uint32_t sequenceLength(const char* field, std::size_t min_element_bytes);
  /// A time (ROS 1 time / builtin_interfaces/Time) in ns.
  std::int64_t time(const char* field);
  /// A std_msgs/Header: stamp [ns] and frame_id (ROS 1's seq is skipped).
  std::int64_t header(std::string& frame_id);
  /// `n` raw bytes (uint8 arrays), not aligned.
  const std::uint8_t* bytes(std::size_t n, const char* field);

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return size_ - pos_; }
  WireFormat format() const { return format_; }

 private:
  void align(std::size_t n);
  void need(std::size_t n, const char* field) const;

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
  std::size_t origin_ = 0;  ///< where alignment is counted from (after the CDR header)
  WireFormat format_;
  bool big_endian_ = false;
};

/// Writes little-endian ROS 1 serialization or little-endian CDR (with its header).
class WireWriter {
 public:
  explicit WireWriter(WireFormat format);
  void u8(std::uint8_t v);
  void boolean(bool v) { u8(v ? 1 : 0); }
  void u16(std::uint16_t v);
  void u32(std::uint32_t v);
  void i32(std::int32_t v) { u32(static_cast<std::uint32_t>(v)); }
  void f64(double v);
  void string(const std::string& s);
  void time(std::int64_t ns);
  /// std_msgs/Header (ROS 1: with `seq`).
  void header(std::int64_t stamp_ns, const std::string& frame_id, std::uint32_t seq = 0);
  void bytes(const std::uint8_t* data, std::size_t n);

  std::vector<std::uint8_t>& buffer() { return out_; }
  std::vector<std::uint8_t> take() { return std::move(out_); }

 private:
  void align(std::size_t n);
  WireFormat format_;
  std::vector<std::uint8_t> out_;
  std::size_t origin_ = 0;
};

}  // namespace storey
