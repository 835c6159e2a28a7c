#pragma once
/// MCAP files (https://mcap.dev/spec), read without an MCAP library: the
/// magic, the Header, the data section record by record (Schema, Channel,
/// Message, Chunk with "", "zstd" or "lz4" compression, the rest skipped),
/// Data End, and when present the summary section (Schema, Channel,
/// Statistics) and the Footer. Messages are delivered in file order, one
/// chunk decompressed in memory at a time.
///
/// Checked: both magics, every record's length against the file, the chunk
/// CRCs (uncompressed_crc), the data section CRC (Data End) and the summary
/// CRC (Footer) when not 0, schema and channel references. A file cut short
/// (no Data End / Footer) is read up to its last complete record, with one
/// warning naming the byte where it ends.
#include <cstdint>
#include <memory>
#include <string>

#include "io/ros2_storage.h"

namespace storey {

/// The 8 magic bytes that start and end an MCAP file: 0x89 "MCAP0\r\n".
inline constexpr char kMcapMagic[] = "\x89MCAP0\r\n";
inline constexpr std::size_t kMcapMagicSize = 8;

bool isMcapMagic(const std::string& head);

/// Opens an MCAP file. Throws storey::Error naming the file and byte offset
/// when it is not MCAP, damaged (bad lengths, CRC mismatch, unknown
/// compression, missing schema or channel) or holds no channel.
std::unique_ptr<MessageStorage> openMcapStorage(const std::string& path);

}  // namespace storey
