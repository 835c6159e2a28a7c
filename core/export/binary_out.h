#pragma once
/// Little-endian binary output helpers for the writers (x86-64 and ARM64 are
/// little-endian; a static_assert-free memcpy keeps the intent explicit).
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <vector>

namespace storey::binary {

template <typename T>
inline void put(std::string& buffer, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  buffer.append(bytes, sizeof(T));
}

/// Fixed-size, zero-padded character field.
inline void putChars(std::string& buffer, const std::string& text, std::size_t size) {
  std::string field = text.substr(0, size);
  field.resize(size, '\0');
  buffer += field;
}

/// Writes `value` at `at` and returns the byte after it.
template <typename T>
inline char* putAt(char* at, T value) {
  std::memcpy(at, &value, sizeof(T));
  return at + sizeof(T);
}

/// Records of a fixed size written into a buffer of many and passed to a
/// stream whole: each field is one store (putAt), not an append that checks
/// and grows a string.
class RecordBuffer {
 public:
  RecordBuffer(std::ostream& out, std::size_t record_size, std::size_t records = 1 << 16)
      : out_(out), record_size_(record_size), bytes_(record_size * records) {}

  /// Room for the next record (record_size bytes, to be filled by the caller).
  char* next() {
    if (used_ + record_size_ > bytes_.size()) flush();
    char* at = bytes_.data() + used_;
    used_ += record_size_;
    return at;
  }

  /// Passes the records so far to the stream; call once after the last one.
  void flush() {
    out_.write(bytes_.data(), static_cast<std::streamsize>(used_));
    used_ = 0;
  }

 private:
  std::ostream& out_;
  std::size_t record_size_;
  std::vector<char> bytes_;
  std::size_t used_ = 0;
};

}  // namespace storey::binary
