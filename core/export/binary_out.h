#pragma once
/// Little-endian binary output helpers for the writers (x86-64 and ARM64 are
/// little-endian; a static_assert-free memcpy keeps the intent explicit).
#include <cstdint>
#include <cstring>
#include <string>

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

}  // namespace storey::binary
