#include "io/ros_wire.h"

#include <cstring>

#include "common/error.h"

namespace storey {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

std::string hex4(std::uint8_t a, std::uint8_t b) {
  static const char* digits = "0123456789ABCDEF";
  std::string s = "0x";
  for (std::uint8_t v : {a, b}) {
    s += digits[v >> 4];
    s += digits[v & 15];
  }
  return s;
}

}  // namespace

WireReader::WireReader(const std::uint8_t* data, std::size_t size, WireFormat format)
    : data_(data), size_(size), format_(format) {
  if (format_ != WireFormat::kCdr) return;
  if (size_ < 4) {
    throw Error("CDR message of " + std::to_string(size_) +
                " bytes, shorter than its 4-byte encapsulation header");
  }
  if (data_[0] != 0x00 || data_[1] > 0x01) {
    const char* what = data_[0] == 0x00 && (data_[1] == 0x02 || data_[1] == 0x03)
                           ? " (parameter-list CDR)"
                       : data_[0] == 0x00 && data_[1] >= 0x06 && data_[1] <= 0x0B ? " (XCDR2)"
                                                                                  : "";
    throw Error("CDR encapsulation " + hex4(data_[0], data_[1]) + what +
                " is not supported (Storey reads plain CDR, 0x0000 and 0x0001)");
  }
  big_endian_ = data_[1] == 0x00;
  pos_ = origin_ = 4;
}

void WireReader::need(std::size_t n, const char* field) const {
  if (n > size_ - pos_) {
    throw Error(std::string("message ends inside field '") + field + "' (needs " +
                std::to_string(n) + " bytes at byte " + std::to_string(pos_) + ", message has " +
                std::to_string(size_) + ")");
  }
}

void WireReader::align(std::size_t n) {
  if (format_ != WireFormat::kCdr) return;
  const std::size_t rel = (pos_ - origin_) % n;
  if (rel == 0) return;
  const std::size_t pad = n - rel;
  if (pad > size_ - pos_) {
    pos_ = size_;
    return;  // the following read reports the end
  }
  pos_ += pad;
}

std::uint8_t WireReader::u8(const char* field) {
  need(1, field);
  return data_[pos_++];
}

std::uint16_t WireReader::u16(const char* field) {
  align(2);
  need(2, field);
  const std::uint8_t* p = data_ + pos_;
  pos_ += 2;
  return big_endian_ ? static_cast<std::uint16_t>((p[0] << 8) | p[1])
                     : static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}

std::uint32_t WireReader::u32(const char* field) {
  align(4);
  need(4, field);
  const std::uint8_t* p = data_ + pos_;
  pos_ += 4;
  std::uint32_t v = 0;
  for (int k = 0; k < 4; ++k) v |= std::uint32_t{p[big_endian_ ? 3 - k : k]} << (8 * k);
  return v;
}

double WireReader::f64(const char* field) {
  align(8);
  need(8, field);
  const std::uint8_t* p = data_ + pos_;
  pos_ += 8;
  std::uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v |= std::uint64_t{p[big_endian_ ? 7 - k : k]} << (8 * k);
  double d;
  std::memcpy(&d, &v, 8);
  return d;
}

std::string WireReader::string(const char* field) {
  const std::uint32_t n = u32(field);
  need(n, field);
  std::size_t length = n;
  if (format_ == WireFormat::kCdr && length > 0 && data_[pos_ + length - 1] == 0) --length;
  std::string s(reinterpret_cast<const char*>(data_ + pos_), length);
  pos_ += n;
  return s;
}

std::uint32_t WireReader::sequenceLength(const char* field, std::size_t min_element_bytes) {
  const std::uint32_t n = u32(field);
  if (min_element_bytes > 0 && n > remaining() / min_element_bytes) {
    throw Error(std::string("field '") + field + "' claims " + std::to_string(n) +
                " elements but only " + std::to_string(remaining()) + " bytes follow (byte " +
                std::to_string(pos_) + ")");
  }
  return n;
}

std::int64_t WireReader::time(const char* field) {
  if (format_ == WireFormat::kRos1) {
    const std::uint32_t sec = u32(field);
    const std::uint32_t nsec = u32(field);
    return std::int64_t{sec} * kNsPerS + nsec;
  }
  const std::int32_t sec = i32(field);
  const std::uint32_t nsec = u32(field);
  return std::int64_t{sec} * kNsPerS + nsec;
}

std::int64_t WireReader::header(std::string& frame_id) {
  if (format_ == WireFormat::kRos1) u32("header.seq");
  const std::int64_t stamp = time("header.stamp");
  frame_id = string("header.frame_id");
  return stamp;
}

const std::uint8_t* WireReader::bytes(std::size_t n, const char* field) {
  need(n, field);
  const std::uint8_t* p = data_ + pos_;
  pos_ += n;
  return p;
}

WireWriter::WireWriter(WireFormat format) : format_(format) {
  if (format_ == WireFormat::kCdr) {
    out_ = {0x00, 0x01, 0x00, 0x00};  // plain CDR, little-endian
    origin_ = 4;
  }
}

void WireWriter::align(std::size_t n) {
  if (format_ != WireFormat::kCdr) return;
  while ((out_.size() - origin_) % n != 0) out_.push_back(0);
}

void WireWriter::u8(std::uint8_t v) {
  out_.push_back(v);
}
void WireWriter::u16(std::uint16_t v) {
  align(2);
  out_.push_back(static_cast<std::uint8_t>(v));
  out_.push_back(static_cast<std::uint8_t>(v >> 8));
}
void WireWriter::u32(std::uint32_t v) {
  align(4);
  for (int k = 0; k < 4; ++k) out_.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}
void WireWriter::f64(double d) {
  align(8);
  std::uint64_t v;
  std::memcpy(&v, &d, 8);
  for (int k = 0; k < 8; ++k) out_.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
}
void WireWriter::string(const std::string& s) {
  const bool cdr = format_ == WireFormat::kCdr;
  u32(static_cast<std::uint32_t>(s.size() + (cdr ? 1 : 0)));
  out_.insert(out_.end(), s.begin(), s.end());
  if (cdr) out_.push_back(0);
}
void WireWriter::time(std::int64_t ns) {
  std::int64_t sec = ns / kNsPerS, nsec = ns % kNsPerS;
  if (nsec < 0) {
    nsec += kNsPerS;
    --sec;
  }
  u32(static_cast<std::uint32_t>(sec));
  u32(static_cast<std::uint32_t>(nsec));
}
void WireWriter::header(std::int64_t stamp_ns, const std::string& frame_id, std::uint32_t seq) {
  if (format_ == WireFormat::kRos1) u32(seq);
  time(stamp_ns);
  string(frame_id);
}
void WireWriter::bytes(const std::uint8_t* data, std::size_t n) {
  out_.insert(out_.end(), data, data + n);
}

}  // namespace storey
