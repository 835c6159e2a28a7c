#include "io/rosbag2_metadata.h"

#include <yaml-cpp/yaml.h>

#include "common/error.h"

namespace storey {

Rosbag2Metadata readRosbag2Metadata(const std::string& path) {
  Rosbag2Metadata out;
  try {
    const YAML::Node root = YAML::LoadFile(path);
    const YAML::Node info = root["rosbag2_bagfile_information"];
    if (!info || !info.IsMap()) {
      throw Error(path + ": not a rosbag2 metadata file (no rosbag2_bagfile_information)");
    }
    if (info["version"]) out.version = info["version"].as<int>();
    if (info["storage_identifier"]) {
      out.storage_identifier = info["storage_identifier"].as<std::string>();
    }
    if (info["relative_file_paths"]) {
      for (const auto& f : info["relative_file_paths"]) {
        out.relative_file_paths.push_back(f.as<std::string>());
      }
    }
    if (info["compression_format"]) {
      out.compression_format = info["compression_format"].as<std::string>();
    }
    if (info["compression_mode"]) {
      out.compression_mode = info["compression_mode"].as<std::string>();
    }
  } catch (const YAML::Exception& e) {
    throw Error(path + ": cannot read the rosbag2 metadata: " + e.what());
  }
  return out;
}

}  // namespace storey
