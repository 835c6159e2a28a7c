// The `storey` command line: the only file that includes CLI11 (slow to
// compile). It parses options into the structs of commands.h and calls the
// command functions; every storey::Error ends as one line on stderr and exit 1.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>

#include "commands.h"
#include "common/error.h"
#include "common/version.h"
#include "fleet_task.h"
#include "progress_bar.h"

namespace {

void addCommonOptions(CLI::App& cmd, storey::cli::CommonOptions& common) {
  cmd.add_option("-c,--config", common.config_path,
                 "configuration file (YAML); default: built-in defaults, see "
                 "resources/config/default.yaml");
  cmd.add_option("--calibration", common.calibration_path,
                 "sensor calibration file (T_imu_lidar, time offset, IMU noise), format of "
                 "docs/formats.md");
  cmd.add_option("--points-topic", common.points_topic, "point cloud topic (default: auto-detect)");
  cmd.add_option("--imu-topic", common.imu_topic, "IMU topic (default: auto-detect)");
  cmd.add_option("--imu-csv", common.imu_csv,
                 "IMU samples (CSV, docs/formats.md) for a Velodyne pcap or a PCD folder");
  cmd.add_option("--imu-time-offset", common.imu_csv_time_offset,
                 "seconds added to the IMU CSV stamps to put them on the LiDAR's clock");
  cmd.add_option(
      "--velodyne-calibration", common.velodyne_calibration,
      "VeloView calibration XML for a Velodyne pcap (default: the model's datasheet table)");
  cmd.add_option("--velodyne-cut-angle", common.velodyne_cut_angle_deg,
                 "azimuth [deg, 0..360) where Velodyne packets (pcap, VelodyneScan) are cut into "
                 "scans (default 0: where the azimuth wraps; the calibration file's "
                 "lidar.cut_angle_deg)");
}

}  // namespace

int main(int argc, char** argv) {
  using namespace storey::cli;
  installLogSink();  // log messages above the progress bars
  CLI::App app{
      "Storey: LiDAR-inertial SLAM for multi-storey buildings. A log in, one registered point "
      "cloud split into storeys out.",
      "storey"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("storey ") + storey::storeyVersion());

  RunOptions run;
  auto* run_cmd = app.add_subcommand(
      "run", "map a log (ROS1 bag); without LOG the built-in simulated building is mapped");
  run_cmd->add_option(
      "LOG", run.log_path,
      "input log: ROS1 bag, Velodyne pcap (+ --imu-csv) or PCD folder (+ --imu-csv)");
  run_cmd->add_option("-o,--out", run.out_dir, "output folder")->capture_default_str();
  run_cmd->add_flag("--no-srp", run.no_srp, "switch the SRP back end off (odometry only)");
  run_cmd->add_flag("--no-render", run.no_render,
                    "no PNG renders at the end (render them later with `storey render OUT`)");
  run_cmd
      ->add_option("--threads", run.threads,
                   "threads: 1 = all on one thread (no read-ahead of the log, the back end on the "
                   "odometry's "
                   "thread); 0 = all cores. The "
                   "outputs are the same bytes either way")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  run_cmd
      ->add_option("--preset", run.preset,
                   "without LOG: the simulated building to map (tiny, default, building-a, "
                   "building-b, long-walk, or random:SEED)")
      ->capture_default_str();
  addCommonOptions(*run_cmd, run.common);

  InfoOptions info;
  auto* info_cmd = app.add_subcommand(
      "info", "describe a log: topics, types, counts, rates, durations, point fields");
  info_cmd->add_option("LOG", info.log_path, "input log")->required();
  addCommonOptions(*info_cmd, info.common);

  SimulateOptions simulate;
  auto* sim_cmd = app.add_subcommand(
      "simulate",
      "simulate a multi-storey building walk: LiDAR (VLP-16, VLP-32C, HDL-32E, OS1-64) + IMU in a "
      "ROS1 bag and/or a Velodyne pcap, with ground truth");
  sim_cmd
      ->add_option("BUILDING", simulate.preset_or_spec,
                   "preset (tiny, default, building-a, building-b, long-walk), random:SEED (a "
                   "random building, "
                   "sensor rig and walk) or building spec YAML")
      ->capture_default_str();
  sim_cmd->add_option("-o,--out", simulate.out_dir, "output folder")->required();
  sim_cmd->add_option("--seed", simulate.seed, "random seed (default: the spec's)");
  sim_cmd->add_option("--range-noise", simulate.range_noise, "LiDAR range noise sigma [m]");
  sim_cmd->add_option("--imu-rate", simulate.imu_rate_hz, "IMU rate [Hz]");
  sim_cmd->add_option("--lidar", simulate.lidar,
                      "LiDAR model instead of the spec's: VLP-16, VLP-32C, HDL-32E, OS1-64");
  sim_cmd->add_option("--imu", simulate.imu,
                      "IMU grade instead of the spec's: tactical or consumer, optionally @HZ "
                      "(consumer@100)");
  sim_cmd->add_option("--motion", simulate.motion, "legged or handheld instead of the spec's");
  sim_cmd->add_option("--fault", simulate.faults,
                      "inject a fault into the logs (repeatable): imu_spike@T (one full-range "
                      "sample), imu_gap@T+D, lidar_gap@T+D, imu_saturation@T+D, occlusion@T+D, "
                      "duplicate@T+D, reorder@T+D, nan@T+D, imu_clock_jump@T+S, "
                      "lidar_clock_jump@T+S (T, D in seconds from the start; S the stamps' step, "
                      "signed: @T+S or @T-S)");
  bool no_progress = false;
  sim_cmd->add_flag("--no-progress", no_progress, "no progress bar");
  sim_cmd->add_flag("--perfect-sensors", simulate.perfect_sensors,
                    "no noise, dropouts or biases (for tests)");
  bool no_compress = false;
  sim_cmd->add_flag("--no-compress", no_compress, "plain bag chunks instead of LZ4");
  sim_cmd->add_option("--duration", simulate.max_duration, "stop the sensors after this time [s]");
  sim_cmd->add_option("--start-at", simulate.start_at,
                      "leave out the logs before this time [s]: a log that starts while moving "
                      "(the walk stands still for its first 2 s)");
  sim_cmd->add_option("--threads", simulate.threads, "ray-casting threads (0: all cores)")
      ->capture_default_str();
  sim_cmd->add_flag(
      "--pcap", simulate.pcap,
      "also write simulation.pcap (Velodyne packets as VeloView records them) + imu.csv");
  sim_cmd->add_flag_callback(
      "--no-bag", [&simulate] { simulate.bag = false; }, "no ROS1 bag (with --pcap or --ros2)");
  sim_cmd
      ->add_option("--ros2", simulate.ros2,
                   "also write a ROS 2 bag (simulation_ros2/: metadata.yaml + sqlite3 .db3 or "
                   ".mcap, CDR messages)")
      ->check(CLI::IsMember({"db3", "mcap"}));
  sim_cmd
      ->add_option("--compression", simulate.mcap_compression,
                   "chunk compression of the ROS 2 bag's MCAP file")
      ->check(CLI::IsMember({"none", "zstd", "lz4"}))
      ->capture_default_str();
  sim_cmd->add_flag("--packets", simulate.packets,
                    "the LiDAR as velodyne_msgs/VelodyneScan packets on /velodyne_packets in the "
                    "bags, not point clouds (Velodyne models)");

  EvalOptions eval;
  auto* eval_cmd = app.add_subcommand(
      "eval", "compare an estimated trajectory with ground truth (ATE, RPE, end-point drift)");
  eval_cmd->add_option("--gt", eval.gt_path, "ground-truth trajectory (TUM)")->required();
  eval_cmd->add_option("--est", eval.est_path, "estimated trajectory (TUM)")->required();
  eval_cmd->add_option("--mesh", eval.mesh_path, "true building mesh (PLY)");
  eval_cmd->add_option("--map", eval.map_path, "registered map (PLY)");
  eval_cmd->add_option("--storeys", eval.storeys_path, "true storey elevations (YAML)");
  eval_cmd->add_option("--est-storeys", eval.est_storeys_path,
                       "estimated storeys.json (default: storeys.json next to --est)");
  eval_cmd->add_option("--planes", eval.planes_path,
                       "planes.json of the run: plane associations checked with the true poses");
  eval_cmd->add_option("--json", eval.json_path,
                       "JSON result file (default: <est>.eval.json; 'none': no file; '-': stdout)");
  eval_cmd->add_option("--rpe-length", eval.rpe_lengths, "RPE segment length [m], repeatable")
      ->capture_default_str();
  eval_cmd
      ->add_option("--max-dt", eval.max_time_difference,
                   "timestamp tolerance of the association [s]")
      ->capture_default_str();
  eval_cmd->add_option("--threads", eval.threads, "map distance threads (0: all cores)")
      ->capture_default_str();

  RegistrationBiasOptions bias;
  auto* bias_cmd = app.add_subcommand(
      "registration-bias",
      "the odometry's registration step at the TRUE poses against a map built from them: "
      "where the LiDAR measurement itself pulls the estimate away (docs/evaluation.md)");
  bias_cmd->add_option("LOG", bias.log_path, "input log (e.g. a simulation.bag)")->required();
  bias_cmd->add_option("--gt", bias.gt_path, "the LiDAR's true trajectory (TUM)")->required();
  bias_cmd->add_option("--csv", bias.csv_path, "per-scan table (CSV)");
  bias_cmd->add_option("--from", bias.from, "first scan evaluated [s after the log's first scan]");
  bias_cmd->add_option("--to", bias.to, "last scan evaluated [s after the log's first scan]");
  bias_cmd
      ->add_option("--max-dt", bias.max_time_difference,
                   "truth stamp tolerance at the ends of the truth [s]")
      ->capture_default_str();
  bias_cmd->add_option("--gt-imu", bias.gt_imu_path,
                       "the IMU's true trajectory at its rate (TUM, e.g. groundtruth_imu.tum): "
                       "each point deskewed with its own true pose (needs the calibration's "
                       "T_imu_lidar)");
  bias_cmd->add_option("--storeys", bias.storeys_path,
                       "the true storeys (the simulator's storeys.yaml): also summarise the "
                       "scans on a storey and on the stairs apart");
  addCommonOptions(*bias_cmd, bias.common);

  RenderOptions render;
  auto* render_cmd =
      app.add_subcommand("render", "write PNG renders of a `storey run` output folder, off-screen");
  render_cmd->add_option("OUTDIR", render.out_dir, "output folder of storey run")->required();
  render_cmd->add_option("-c,--config", render.config_path,
                         "configuration file (YAML); its render: section is used");
  render_cmd->add_option("--keyframe", render.keyframe,
                         "keyframe of the SRP keyframe view (index into keyframes.tum; default: "
                         "the one with the most SRPs)");
  render_cmd->add_option("--gt", render.ground_truth,
                         "ground-truth trajectory (TUM): adds estimated vs true trajectory views");
  render_cmd->add_option("--compare", render.compare,
                         "another run's output folder (e.g. its --no-srp run) drawn with --gt; "
                         "repeatable");
  render_cmd->add_option("--width", render.width, "image width [px] (default 1600)");
  render_cmd->add_option("--height", render.height, "image height [px] (default 1000)");
  render_cmd->add_option("--views", render.views,
                         "images to write, comma-separated: elevation, storeys, srp, keyframe, "
                         "trajectories, all (default: all)");
  render_cmd->add_option("--max-points", render.max_points,
                         "map points drawn at most (uniform subsample; default 2000000)");

  StoreysOptions storeys;
  auto* storeys_cmd = app.add_subcommand(
      "storeys",
      "split a finished run's map into storeys again (map.ply and keyframes.tum of `storey run`), "
      "e.g. with other storeys: settings, without mapping the log again");
  storeys_cmd->add_option("RUN_DIR", storeys.run_dir, "output folder of storey run")->required();
  storeys_cmd
      ->add_option("-o,--out", storeys.out_dir,
                   "output folder: map files, storeys/ and storeys.json (not RUN_DIR)")
      ->required();
  storeys_cmd->add_option("-c,--config", storeys.config_path,
                          "configuration file (YAML); its storeys: section is used");

  BenchOptions bench;
  auto* bench_cmd = app.add_subcommand(
      "bench",
      "benchmark on random buildings: simulate random:SEED, map it with default settings (or -c), "
      "evaluate; one table with a row per seed and the distributions (docs/benchmarks.md)");
  bench_cmd->add_option("--seeds", bench.seeds, "seeds: 1-30, 1,4,9 or 1-10,1001-1010")
      ->capture_default_str();
  bench_cmd
      ->add_option("-o,--out", bench.out_dir,
                   "output folder (a folder per seed, "
                   "benchmark.md, benchmark.json)")
      ->required();
  bench_cmd->add_option("--jobs", bench.jobs, "seeds at a time (0: the number of cores)")
      ->capture_default_str();
  bench_cmd->add_option("--duration", bench.max_duration,
                        "simulate only the first S seconds of each walk (quick checks)");
  bench_cmd->add_flag("--keep", bench.keep, "keep every seed's bag, mesh and map");
  bench_cmd->add_flag("--resume", bench.resume,
                      "keep the seeds that an earlier bench into the same folder finished "
                      "(with the same --duration and configuration) and run only the others");
  bench_cmd
      ->add_flag("--retry-failed", bench.retry_failed,
                 "with --resume: run the seeds that failed earlier again (a full disk, a killed "
                 "process); without it a failed seed is kept as a finished row")
      ->needs("--resume");
  bench_cmd->add_option("-c,--config", bench.config,
                        "map every seed with this configuration (YAML, as `storey run -c`) "
                        "instead of the defaults");

  BatchOptions batch;
  auto* batch_cmd = app.add_subcommand(
      "batch",
      "map many logs (storey run each, one output folder per log), resumable, on this machine or "
      "on a Slurm cluster; fleet.json and fleet.html at the end (docs/batch.md)");
  batch_cmd->add_option("INPUTS", batch.inputs,
                        "logs (files or PCD folders), folders to search for logs (*.bag, *.pcap, "
                        "*.pcapng, PCD folders), manifests (YAML with logs:, docs/batch.md)");
  batch_cmd->add_option("-o,--out", batch.out_dir,
                        "FLEET_OUT: logs/<name>/ per log, state/, fleet.json, fleet.html");
  batch_cmd->add_option("--executor", batch.executor, "local (processes here) or slurm")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  batch_cmd
      ->add_option("--jobs", batch.jobs,
                   "local: logs at a time (0: cores / threads one run uses); slurm: array "
                   "tasks running at once (%M; 0: no limit)")
      ->capture_default_str();
  batch_cmd->add_option("-c,--config", batch.config_path,
                        "configuration of every log (YAML; a manifest's per-log config: goes "
                        "over it)");
  batch_cmd->add_option("--calibration", batch.calibration_path,
                        "sensor calibration for the logs without their own (manifest)");
  batch_cmd->add_option("--retries", batch.retries, "attempts after a failed run of a log")
      ->capture_default_str();
  batch_cmd->add_flag("--only-failed", batch.only_failed,
                      "run only the logs whose last run failed");
  batch_cmd->add_flag("--force", batch.force, "run every log again, even when finished");
  batch_cmd->add_option("--status", batch.status_dir,
                        "FLEET_OUT: show a batch's state, collect a finished Slurm batch, rewrite "
                        "its report (no INPUTS)");
  batch_cmd->add_flag("--submit-only", batch.submit_only,
                      "slurm: submit the job array and a collect job, then return");
  batch_cmd->add_option("--partition", batch.partition, "slurm: partition (sbatch --partition)");
  batch_cmd->add_option("--account", batch.account, "slurm: account (sbatch --account)");
  batch_cmd->add_option("--cpus-per-task", batch.cpus_per_task, "slurm: CPUs per task (default 1)");
  batch_cmd->add_option("--mem", batch.mem,
                        "slurm: memory per task, sbatch syntax (default: estimated from the "
                        "largest log's size and duration)");
  batch_cmd->add_option("--time", batch.time,
                        "slurm: time limit per task, sbatch syntax (default: estimated from the "
                        "longest log)");
  batch_cmd->add_option("--sbatch-arg", batch.sbatch_args,
                        "slurm: one more sbatch argument, e.g. --sbatch-arg=--qos=short "
                        "(repeatable)");
  batch_cmd->add_option("--task-prolog", batch.prolog,
                        "slurm: shell line(s) each task runs before storey, e.g. 'module load "
                        "storey'");
  batch_cmd->add_option("--storey", batch.storey_binary,
                        "slurm: the storey binary as the compute nodes see it (default: this "
                        "program's path; it must be on a shared file system)");
  batch_cmd->add_option("--poll", batch.poll_seconds, "slurm: seconds between squeue calls")
      ->capture_default_str();

  std::string task_plan;
  int task_index = -1;
  auto* task_cmd = app.add_subcommand("batch-task", "one array task of a Slurm batch (internal)");
  task_cmd->group("");  // hidden from --help
  task_cmd->add_option("PLAN", task_plan, "state/plan-N.json")->required();
  task_cmd->add_option("INDEX", task_index, "task index (SLURM_ARRAY_TASK_ID)")->required();

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  }

  try {
    if (*run_cmd) return runRun(run);
    if (*info_cmd) return runInfo(info);
    if (*sim_cmd) {
      simulate.progress = !no_progress;
      simulate.compress = !no_compress;
      return runSimulate(simulate);
    }
    if (*eval_cmd) return runEval(eval);
    if (*render_cmd) return runRender(render);
    if (*storeys_cmd) return runStoreys(storeys);
    if (*bench_cmd) return runBench(bench);
    if (*bias_cmd) return runRegistrationBias(bias);
    if (*batch_cmd) return runBatch(batch);
    if (*task_cmd) return runBatchTask(task_plan, task_index);
  } catch (const storey::Cancelled& e) {
    std::cerr << "storey: " << e.what() << '\n';
    return 1;
  } catch (const storey::Error& e) {
    std::cerr << "storey: error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "storey: internal error: " << e.what() << '\n';
    return 1;
  }
  return 1;
}
