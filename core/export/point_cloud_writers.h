#pragma once
/// Map exports: LAS 1.4, binary PLY and binary PCD of a MapCloud (or of the
/// points named by `indices`). Every file is written atomically (temporary
/// name, then rename). Formats and fields: docs/outputs.md.
#include <cstdint>
#include <string>
#include <vector>

#include "map/map_cloud.h"

namespace storey {

/// LAS 1.4 point data record format 6 and its extra bytes (docs/outputs.md).
namespace las {
inline constexpr double kScale = 0.001;               ///< coordinate resolution [m]
inline constexpr std::uint16_t kHeaderSize = 375;
inline constexpr std::uint8_t kPointFormat = 6;
inline constexpr std::uint16_t kPointFormatSize = 30;  ///< PDRF 6 without extra bytes
inline constexpr std::uint16_t kExtraBytes = 7;        ///< storey int16, keyframe int32, flags uint8
inline constexpr std::uint16_t kRecordLength = kPointFormatSize + kExtraBytes;
}  // namespace las

/// Whole cloud (`indices` null) or the listed points.
void writeLas(const std::string& path, const MapCloud& cloud,
              const std::vector<std::uint32_t>* indices = nullptr);
void writePly(const std::string& path, const MapCloud& cloud,
              const std::vector<std::uint32_t>* indices = nullptr);
void writePcd(const std::string& path, const MapCloud& cloud,
              const std::vector<std::uint32_t>* indices = nullptr);

}  // namespace storey
