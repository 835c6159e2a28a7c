#pragma once
/// Reading of PCD files (Point Cloud Library format, v0.5-0.7; DATA ascii,
/// binary or binary_compressed) into a point-cloud layout and packed bytes,
/// without PCL. Fields of type U8/I8 (64-bit integers) are converted to
/// float64 so the generic point-cloud decoder can read them.
#include <cstdint>
#include <string>
#include <vector>

#include "io/point_cloud_layout.h"

namespace storey {

struct PcdHeader {
  std::string version;
  std::vector<PointFieldDesc> fields;  ///< offsets in the packed point
  std::uint32_t point_step = 0;        ///< bytes per packed point
  std::uint32_t width = 0, height = 1;
  std::uint64_t points = 0;
  std::string data;  ///< "ascii", "binary" or "binary_compressed"
  std::size_t data_offset = 0;  ///< byte where the data starts
};

struct PcdCloud {
  PcdHeader header;
  std::vector<std::uint8_t> bytes;  ///< packed points (point_step each), little-endian
  PointCloudView view() const;      ///< a view of `bytes` (valid while this lives)
};

/// Reads only the header. Throws storey::Error naming the file and line on a bad header.
PcdHeader readPcdHeader(const std::string& path);
/// Reads the whole file. Throws storey::Error naming the file and what is wrong
/// (header line, byte offset of a truncated body, ascii line) on a bad file.
PcdCloud readPcd(const std::string& path);
/// True when `head` (the first bytes of a file) looks like a PCD header.
bool looksLikePcd(const std::string& head);

/// LZF decompression (as PCL's binary_compressed uses); false on corrupt input.
bool lzfDecompress(const std::uint8_t* in, std::size_t in_size, std::uint8_t* out, std::size_t out_size);

}  // namespace storey
