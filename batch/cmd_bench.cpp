// `storey bench`: random buildings (storey simulate random:SEED), each mapped
// with DEFAULT settings and only its simulated calibration file, evaluated
// against the truth; one table (markdown + JSON) with a row per seed and the
// distribution of each figure. Each step is a child `storey` process (its
// peak memory measured, its log kept); a failing seed is a row with its error.
// A finished seed leaves seed.json; `--resume` keeps such seeds (an interrupted
// or split benchmark goes on where it stopped), `--retry-failed` only those
// that did not fail.

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

#include "bench_table.h"
#include "child_process.h"
#include "commands.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "common/yaml_section.h"
#include "config/config.h"
#include "progress_bar.h"

namespace storey::cli {
namespace {

namespace fs = std::filesystem;

std::vector<std::uint64_t> parseSeeds(const std::string& text) {
  std::vector<std::uint64_t> seeds;
  std::stringstream list(text);
  std::string item;
  while (std::getline(list, item, ',')) {
    try {
      const std::size_t dash = item.find('-');
      if (dash == std::string::npos) {
        seeds.push_back(std::stoull(item));
      } else {
        const std::uint64_t a = std::stoull(item.substr(0, dash)),
                            b = std::stoull(item.substr(dash + 1));
        if (b < a || b - a > 100000) throw Error("");
        for (std::uint64_t s = a; s <= b; ++s) seeds.push_back(s);
      }
    } catch (const std::exception&) {
      throw Error("--seeds '" + text + "': expected seeds like 1-30 or 1,4,9 or 1-10,1001-1010");
    }
  }
  if (seeds.empty()) throw Error("--seeds: no seed given");
  return seeds;
}

std::string fixed(double v, int decimals) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, v);
  return text;
}

/// A finished seed in one line: its error, or storeys, ATE and worst floor.
std::string summary(const BenchRow& row) {
  if (!row.error.empty()) return "FAILED (" + row.error + ")";
  return std::to_string(row.storeys) + " storeys, ATE " + (row.ate_m ? fixed(*row.ate_m, 3) : "?") +
         " m, worst floor " + (row.worst_floor_m ? fixed(*row.worst_floor_m, 3) : "?") + " m";
}

}  // namespace

int runBench(const BenchOptions& options) {
  const std::vector<std::uint64_t> seeds = parseSeeds(options.seeds);
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const int jobs = options.jobs > 0 ? options.jobs : static_cast<int>(cores);
  const int threads = std::max(1, static_cast<int>(cores) / jobs);
  // -c: checked before anything is written or run (a wrong key fails here, once), then
  // passed to every seed's `storey run`; its text goes into each seed's record.
  std::string config_path, config_text;
  if (!options.config.empty()) {
    loadRunConfig(options.config, "");
    config_path = fs::absolute(options.config).string();
    config_text = readTextFile(options.config);
  }

  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) throw Error(options.out_dir + ": cannot create the folder: " + ec.message());

  std::vector<BenchRow> rows(seeds.size());
  std::atomic<std::size_t> next{0};
  std::mutex print;
  std::size_t done = 0;
  std::cerr << "bench: " << seeds.size() << " seeds, " << jobs << " at a time, into "
            << options.out_dir << '\n';
  ProgressBar bar("bench");  // seeds done, elapsed, time left; the seeds' lines above it
  bar.update(0.0, "seeds");

  auto work = [&] {
    for (std::size_t i = next++; i < seeds.size(); i = next++) {
      BenchRow& row = rows[i];
      row.seed = seeds[i];
      const fs::path dir = fs::path(options.out_dir) / ("seed-" + std::to_string(row.seed));
      const bool kept = options.resume && readSeedRecord(dir.string(), row.seed,
                                                         options.max_duration, config_text, row);
      if (kept && options.retry_failed && !row.error.empty()) {
        row = BenchRow{};  // failed earlier: run again
        row.seed = seeds[i];
      } else if (kept) {
        std::lock_guard<std::mutex> lock(print);
        ++done;
        bar.print("bench: [" + std::to_string(done) + "/" + std::to_string(seeds.size()) +
                  "] seed " + std::to_string(row.seed) + ": " + summary(row) +
                  " (kept from an earlier run)");
        bar.update(static_cast<double>(done) / static_cast<double>(seeds.size()), "seeds");
        continue;
      }
      fs::remove_all(dir, ec);
      fs::create_directories(dir);
      const std::string sim = (dir / "sim").string(), run = (dir / "run").string();
      std::vector<std::string> simulate{"simulate",
                                        "random:" + std::to_string(row.seed),
                                        "-o",
                                        sim,
                                        "--no-progress",
                                        "--threads",
                                        std::to_string(threads)};
      if (options.max_duration > 0.0)
        simulate.insert(simulate.end(), {"--duration", fixed(options.max_duration, 3)});
      std::vector<std::string> map{"run",
                                   sim + "/simulation.bag",
                                   "--calibration",
                                   sim + "/calibration.yaml",
                                   "-o",
                                   run,
                                   "--no-render"};
      if (!config_path.empty()) map.insert(map.end(), {"-c", config_path});
      const std::vector<std::pair<std::string, std::vector<std::string>>> steps{
          {"simulate", simulate},
          {"run", map},
          {"eval",
           {"eval", "--gt", sim + "/groundtruth_lidar.tum", "--est", run + "/trajectory.tum",
            "--storeys", sim + "/storeys.yaml", "--mesh", sim + "/building.ply", "--map",
            run + "/map.ply", "--json", (dir / "eval.json").string(), "--threads",
            std::to_string(threads)}},
          // The front end alone (run/odometry.tum): is the back end an improvement?
          {"eval_odometry",
           {"eval", "--gt", sim + "/groundtruth_lidar.tum", "--est", run + "/odometry.tum",
            "--json", (dir / "eval_odometry.json").string()}},
          // The back end's plane associations checked with the true poses.
          {"eval_planes",
           {"eval", "--gt", sim + "/groundtruth_lidar.tum", "--est", run + "/trajectory.tum",
            "--planes", run + "/planes.json", "--json", (dir / "eval_planes.json").string()}}};
      for (const auto& [name, args] : steps) {
        const std::string log = (dir / (name + ".log")).string();
        const ChildResult step = runSelf(args, log);
        if (name == "run") row.peak_memory_mb = step.peak_mb;
        if (step.exit_code != 0) {
          row.error = name + ": " + lastLine(log);
          break;
        }
      }
      readBenchRow(dir.string(), row);
      // Written last: the seed is finished (what --resume keeps).
      writeFileAtomically((dir / "seed.json").string(),
                          seedRecordJson(row, options.max_duration, config_text));
      if (!options.keep) {
        // The bulky files; the spec, the reports and the logs stay.
        for (const char* bulky :
             {"sim/simulation.bag", "sim/building.ply", "sim/groundtruth_imu.tum", "run/map.las",
              "run/map.ply", "run/map.pcd", "run/storeys"})
          fs::remove_all(dir / bulky, ec);
      }
      std::lock_guard<std::mutex> lock(print);
      ++done;
      bar.print("bench: [" + std::to_string(done) + "/" + std::to_string(seeds.size()) + "] seed " +
                std::to_string(row.seed) + ": " + summary(row));
      bar.update(static_cast<double>(done) / static_cast<double>(seeds.size()), "seeds");
    }
  };
  std::vector<std::thread> workers;
  for (int j = 0; j < jobs; ++j) workers.emplace_back(work);
  for (std::thread& t : workers) t.join();

  const std::string title = "storey bench --seeds " + options.seeds +
                            (options.config.empty() ? "" : " -c " + options.config);
  writeFileAtomically((fs::path(options.out_dir) / "benchmark.md").string(),
                      benchMarkdown(rows, title));
  writeFileAtomically((fs::path(options.out_dir) / "benchmark.json").string(), benchJson(rows));
  std::cout << benchMarkdown(rows, title) << "\nWrote " << options.out_dir
            << "/benchmark.md and benchmark.json\n";
  return 0;
}

}  // namespace storey::cli
