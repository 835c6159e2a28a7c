#include "export/map_export.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <regex>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/parallel_jobs.h"
#include "export/point_cloud_writers.h"
#include "export/storey_files.h"
#include "export/storeys_json.h"

namespace storey {

namespace fs = std::filesystem;

std::vector<std::string> writeMapFiles(const std::string& out_dir, const MapCloud& map,
                                       const StoreySegmentation& segmentation,
                                       double map_voxel_size, const ProgressFn& progress,
                                       int threads) {
  const fs::path out(out_dir);
  const fs::path storeys_dir = out / "storeys";
  std::error_code ec;
  fs::create_directories(storeys_dir, ec);
  if (ec) throw Error(storeys_dir.string() + ": cannot create the folder: " + ec.message());
  // One job per file (a storey's two files share its point list), each
  // written whole by one thread; reported in this order.
  std::vector<std::function<void()>> jobs;
  std::vector<std::vector<std::string>> names;  // per job, relative to out_dir
  jobs.push_back([&] { writeLas((out / "map.las").string(), map); });
  names.push_back({"map.las"});
  jobs.push_back([&] { writePly((out / "map.ply").string(), map); });
  names.push_back({"map.ply"});
  jobs.push_back([&] { writePcd((out / "map.pcd").string(), map); });
  names.push_back({"map.pcd"});
  std::vector<std::string> kept;
  for (const StoreyInfo& s : segmentation.storeys) {
    const std::string stem = storeyStem(s.index);
    jobs.push_back([&map, &storeys_dir, stem, index = s.index] {
      const std::vector<std::uint32_t> indices = pointsOfStorey(map, index);
      writeLas((storeys_dir / (stem + ".las")).string(), map, &indices);
      writePly((storeys_dir / (stem + ".ply")).string(), map, &indices);
    });
    names.push_back({"storeys/" + stem + ".las", "storeys/" + stem + ".ply"});
    kept.push_back(stem + ".las");
    kept.push_back(stem + ".ply");
  }
  const std::size_t steps = 3 + 2 * segmentation.storeys.size() + 1;
  std::size_t step = 0;
  std::vector<std::string> files;
  auto done = [&](const std::string& file) {
    files.push_back(file);
    if (progress && !progress(static_cast<double>(++step) / static_cast<double>(steps), "export"))
      throw Cancelled();
  };
  runJobs(jobs, threads, [&](std::size_t job) {
    for (const std::string& name : names[job]) done(name);
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
