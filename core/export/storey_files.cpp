#include "export/storey_files.h"

#include <cstdio>
#include <filesystem>
#include <set>

#include "common/error.h"
#include "export/point_cloud_writers.h"

namespace storey {

namespace fs = std::filesystem;

std::vector<int> storeyIndices(const MapCloud& map) {
  std::set<int> seen;
  for (std::int16_t s : map.storey)
    if (s != kNoStorey) seen.insert(s);
  return {seen.begin(), seen.end()};
}

std::vector<std::uint32_t> pointsOfStorey(const MapCloud& map, int storey) {
  std::vector<std::uint32_t> indices;
  for (std::size_t i = 0; i < map.storey.size(); ++i)
    if (map.storey[i] == storey) indices.push_back(static_cast<std::uint32_t>(i));
  return indices;
}

std::string storeyStem(int storey) {
  char stem[32];
  std::snprintf(stem, sizeof(stem), "storey_%02d", storey);
  return stem;
}

std::vector<std::string> writeStoreyFiles(const MapCloud& map, const std::vector<int>& storeys,
                                          const std::string& dir, const StoreyFileFormats& formats,
                                          const std::function<void(const std::string&)>& on_file) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the folder: " + ec.message());
  std::vector<std::string> written;
  auto wrote = [&](const std::string& path) {
    written.push_back(path);
    if (on_file) on_file(path);
  };
  for (int s : storeys) {
    const std::vector<std::uint32_t> indices = pointsOfStorey(map, s);
    const std::string base = (fs::path(dir) / storeyStem(s)).string();
    if (formats.las) {
      writeLas(base + ".las", map, &indices);
      wrote(base + ".las");
    }
    if (formats.ply) {
      writePly(base + ".ply", map, &indices);
      wrote(base + ".ply");
    }
  }
  return written;
}

std::vector<std::string> writeStoreyFiles(const MapCloud& map, const std::string& dir,
                                          const StoreyFileFormats& formats) {
  const std::vector<int> storeys = storeyIndices(map);
  if (storeys.empty()) throw Error("the cloud has no storey labels (was storey segmentation on?)");
  return writeStoreyFiles(map, storeys, dir, formats);
}

}  // namespace storey
