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

std::vector<std::string> writeStoreyFiles(const MapCloud& map, const std::string& dir,
                                          const StoreyFileFormats& formats) {
  const std::vector<int> storeys = storeyIndices(map);
  if (storeys.empty()) throw Error("the cloud has no storey labels (was storey segmentation on?)");
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create the folder: " + ec.message());
  std::vector<std::string> written;
  for (int s : storeys) {
    const std::vector<std::uint32_t> indices = pointsOfStorey(map, s);
    char stem[32];
    std::snprintf(stem, sizeof(stem), "storey_%02d", s);
    const std::string base = (fs::path(dir) / stem).string();
    if (formats.las) {
      writeLas(base + ".las", map, &indices);
      written.push_back(base + ".las");
    }
    if (formats.ply) {
      writePly(base + ".ply", map, &indices);
      written.push_back(base + ".ply");
    }
  }
  return written;
}

}  // namespace storey
