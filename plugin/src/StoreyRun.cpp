#include "StoreyRun.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>

#include "common/error.h"
#include "config/config.h"
#include "export/point_cloud_writers.h"

namespace storey::plugin {

namespace fs = std::filesystem;

std::string resolveCalibration(const RunRequest& request) {
  if (!request.calibration_path.empty()) return request.calibration_path;
  const fs::path log(request.log_path);
  // A PCD folder's calibration sits inside it; a file's beside it.
  const fs::path folder = fs::is_directory(log) ? log : log.parent_path();
  const fs::path beside = folder / "calibration.yaml";
  std::error_code ec;
  return fs::is_regular_file(beside, ec) ? beside.string() : std::string();
}

std::string resolveOutDir(const RunRequest& request) {
  if (!request.out_dir.empty()) return request.out_dir;
  fs::path log(request.log_path);
  if (!log.has_filename()) log = log.parent_path();  // "folder/" of a PCD folder
  return (log.parent_path() / (log.stem().string() + "_storey")).string();
}

Config loadRequestConfig(const RunRequest& request) {
  return loadRunConfig(request.config_path, resolveCalibration(request));
}

RunOutcome runStorey(const RunRequest& request, const Config& config, const ProgressFn& progress) {
  if (request.log_path.empty()) throw Error("no log given");
  std::error_code ec;
  if (!fs::exists(request.log_path, ec)) throw Error(request.log_path + ": no such file or folder");
  RunOutcome outcome;
  outcome.log_path = request.log_path;
  outcome.out_dir = resolveOutDir(request);
  outcome.calibration_path = resolveCalibration(request);
  const auto start = std::chrono::steady_clock::now();
  outcome.result = runPipeline(request.log_path, config, outcome.out_dir, progress);
  outcome.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return outcome;
}

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

std::vector<std::string> exportStoreys(const MapCloud& map, const std::string& dir,
                                       const StoreyExportFormats& formats) {
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
    const fs::path base = fs::path(dir) / stem;
    if (formats.las) {
      writeLas(base.string() + ".las", map, &indices);
      written.push_back(base.string() + ".las");
    }
    if (formats.ply) {
      writePly(base.string() + ".ply", map, &indices);
      written.push_back(base.string() + ".ply");
    }
  }
  return written;
}

}  // namespace storey::plugin
