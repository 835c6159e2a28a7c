#pragma once
/// Checks the framing of a ROS1 bag (format 2.0) before librosbag reads it.
/// librosbag trusts the offsets and lengths it finds in a file; some damaged
/// files make it abort (assertions) or read outside its buffers. This check
/// reads only record headers and index records (seeking over message data),
/// so that librosbag is handed only files whose structure is sound.
///
/// Checked: the version line; the file header record (index position inside
/// the file, not 0 = unindexed, no encryption); every connection and chunk
/// info record of the index section; every chunk header (position, known
/// compression, data inside the file) and the index records after it (known
/// connection, entries inside the chunk). For uncompressed chunks every
/// record inside the chunk is framed and every index entry must point at a
/// message record. Compressed chunks (lz4, bz2) are checked up to their sizes.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace storey {

struct RosbagStructure {
  std::uint64_t file_size = 0;  ///< [bytes]
  std::uint64_t index_pos = 0;  ///< byte offset of the index section
  std::uint32_t connection_count = 0;
  std::uint32_t chunk_count = 0;
  std::uint64_t message_count = 0;                             ///< index entries of all chunks
  std::map<std::string, std::uint32_t> chunks_by_compression;  ///< "none" / "lz4" / "bz2" -> chunks
  std::vector<std::uint64_t> chunk_positions;  ///< byte offset of each chunk record, index order
  std::int64_t start_ns = 0;                   ///< earliest message time of the chunk index [ns]
  std::int64_t end_ns = 0;                     ///< latest message time of the chunk index [ns]
};

/// Returns the structure of a sound bag. Throws storey::Error naming `path`,
/// the byte offset and what is wrong for an empty, non-bag, unsupported
/// (version, encryption), unindexed, truncated or damaged file.
RosbagStructure checkRosbagStructure(const std::string& path);

}  // namespace storey
