#include "export/map_export.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <regex>

#include "common/atomic_file.h"
#include "common/error.h"
#include "export/point_cloud_writers.h"
#include "export/storey_files.h"
#include "export/storeys_json.h"

namespace storey {

namespace fs = std::filesystem;

std::vector<std::string> writeMapFiles(const std::string& out_dir, const MapCloud& map,
                                       const StoreySegmentation& segmentation,
                                       double map_voxel_size, const ProgressFn& progress) {
  const fs::path out(out_dir);
  const fs::path storeys_dir = out / "storeys";
  std::error_code ec;
  fs::create_directories(storeys_dir, ec);
  if (ec) throw Error(storeys_dir.string() + ": cannot create the folder: " + ec.message());
  std::vector<std::string> files;
  const std::size_t steps = 3 + 2 * segmentation.storeys.size() + 1;
  std::size_t step = 0;
  auto done = [&](const std::string& file) {
    files.push_back(file);
    if (progress && !progress(static_cast<double>(++step) / static_cast<double>(steps), "export"))
      throw Cancelled();
  };
  writeLas((out / "map.las").string(), map);
  done("map.las");
  writePly((out / "map.ply").string(), map);
  done("map.ply");
  writePcd((out / "map.pcd").string(), map);
  done("map.pcd");

  std::vector<int> storeys;
  for (const StoreyInfo& s : segmentation.storeys) storeys.push_back(s.index);
  std::vector<std::string> kept;
  writeStoreyFiles(map, storeys, storeys_dir.string(), StoreyFileFormats{true, true},
                   [&](const std::string& path) {
                     const std::string name = fs::path(path).filename().string();
                     kept.push_back(name);
                     done("storeys/" + name);
                   });
  // Files of a previous run with more storeys would be mistaken for this run's.
  const std::regex stale("storey_[0-9]+\\.(las|ply)");
  for (const auto& entry : fs::directory_iterator(storeys_dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (std::regex_match(name, stale) && std::find(kept.begin(), kept.end(), name) == kept.end())
      fs::remove(entry.path(), ec);
  }
  writeFileAtomically((out / "storeys.json").string(),
                      storeysJson(segmentation.storeys, map_voxel_size));
  done("storeys.json");
  return files;
}

}  // namespace storey
