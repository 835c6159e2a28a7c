#pragma once
/// rosbag2's metadata.yaml (format versions 1 to 9): the storage, the files
/// of a split bag, compression. Only what reading needs.
#include <string>
#include <vector>

namespace storey {

struct Rosbag2Metadata {
  int version = 0;
  std::string storage_identifier;  ///< "sqlite3" or "mcap"
  std::vector<std::string> relative_file_paths;
  std::string compression_format;  ///< "" or e.g. "zstd"
  std::string compression_mode;    ///< "", "FILE" or "MESSAGE"
};

inline constexpr const char* kRosbag2MetadataFile = "metadata.yaml";

/// Reads `path` (a metadata.yaml). Throws storey::Error naming the file for
/// YAML errors or a file without `rosbag2_bagfile_information`.
Rosbag2Metadata readRosbag2Metadata(const std::string& path);

}  // namespace storey
