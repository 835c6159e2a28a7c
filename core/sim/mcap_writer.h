#pragma once
/// Writes an MCAP file (https://mcap.dev/spec) with the "ros2" profile: CDR
/// messages, ros2msg schemas. Schemas and channels come first in the data
/// section; messages go into chunks (none, zstd or lz4 compressed; each
/// followed by its Message Index records) or, unchunked, into the data
/// section itself; Data End carries the data section's CRC; the summary
/// section (optional) repeats schemas and channels and holds Statistics and
/// Chunk Index records; the Footer its CRC.
#include <cstddef>
#include <memory>
#include <string>

#include "sim/ros2_storage_writer.h"

namespace storey::sim {

enum class McapCompression { kNone, kZstd, kLz4 };

struct McapWriterOptions {
  McapCompression compression = McapCompression::kZstd;
  bool chunked = true;                 ///< messages in chunks (else in the data section)
  bool summary = true;                 ///< write the summary section
  std::size_t chunk_bytes = 4u << 20;  ///< a chunk is closed beyond this size [bytes]
};

/// Creates `path` (replacing it). Throws storey::Error naming the file.
std::unique_ptr<Ros2StorageWriter> openMcapWriter(const std::string& path,
                                                  const McapWriterOptions& options);

}  // namespace storey::sim
