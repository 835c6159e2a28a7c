#pragma once
/// Options and entry points of the `storey` subcommands. Parsing lives in
/// cli.cpp (the one file that includes CLI11); each command's body in its own
/// file, calling core. Every function returns the process exit status and
/// lets storey::Error escape (cli.cpp prints it and returns 1).
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace storey::cli {

struct CommonOptions {
  std::string config_path;       ///< -c/--config; empty = built-in defaults
  std::string calibration_path;  ///< --calibration; empty = none
  std::string points_topic;      ///< --points-topic override
  std::string imu_topic;         ///< --imu-topic override
  std::string imu_csv;           ///< --imu-csv: IMU CSV for a pcap or PCD folder (input.imu_csv)
  std::optional<double> imu_csv_time_offset;  ///< --imu-time-offset: added to the CSV stamps [s]
  std::string
      velodyne_calibration;  ///< --velodyne-calibration: VeloView XML (input.velodyne_calibration)
  /// --velodyne-cut-angle: where Velodyne packets are cut into scans [deg]
  /// (input.velodyne_cut_angle_deg)
  std::optional<double> velodyne_cut_angle_deg;
};

struct RunOptions {
  CommonOptions common;
  std::string log_path;  ///< empty = simulate the built-in default building
  std::string out_dir = "storey_out";
  std::string preset = "default";  ///< building simulated when no log is given
  bool no_srp = false;
  bool no_render = false;  ///< --no-render: no PNG renders at the end (render.enabled = false)
  /// --threads: 1 = everything on the run's thread (input.read_ahead_scans = 0);
  /// 0 (all cores) or more = the configuration's. Same results either way.
  int threads = 0;
};

struct InfoOptions {
  CommonOptions common;
  std::string log_path;
};

struct SimulateOptions {
  std::string preset_or_spec = "default";  ///< preset name or path to a building YAML
  std::string out_dir;
  std::optional<std::uint64_t> seed;
  std::optional<double> range_noise;  ///< [m]
  std::optional<double> imu_rate_hz;  ///< [Hz]
  std::string lidar;                  ///< --lidar: LiDAR model override
  std::string imu;                    ///< --imu: IMU grade override (GRADE or GRADE@HZ)
  std::string motion;                 ///< --motion: legged or handheld
  bool progress = true;
  bool perfect_sensors = false;           ///< --perfect-sensors: no noise, dropouts or biases
  bool compress = true;                   ///< --no-compress clears it: plain (not LZ4) bag chunks
  std::optional<double> max_duration;     ///< --duration: stop the sensors after this time [s]
  double start_at = 0.0;                  ///< --start-at: leave out the log before this time [s]
  int threads = 0;                        ///< --threads: ray-casting threads, 0 = all cores
  bool pcap = false;                      ///< --pcap: also a Velodyne capture + IMU CSV
  bool bag = true;                        ///< --no-bag clears it: no ROS1 bag
  std::string ros2;                       ///< --ros2: "db3" or "mcap"; empty = no ROS 2 bag
  std::string mcap_compression = "zstd";  ///< --compression: none, zstd, lz4 (MCAP chunks)
  bool packets = false;                   ///< --packets: LiDAR as VelodyneScan packets
  std::vector<std::string> faults;        ///< --fault (repeatable): injected faults
};

struct EvalOptions {
  std::string gt_path, est_path, mesh_path, map_path, storeys_path;
  std::string est_storeys_path;  ///< --est-storeys: estimated storeys.json; empty = storeys.json
                                 ///< next to --est
  std::string planes_path;  ///< --planes: planes.json whose associations are checked with the truth
  std::string json_path;  ///< --json: empty = <est stem>.eval.json next to --est; "none" = no file;
                          ///< "-" = JSON on stdout
  std::vector<double> rpe_lengths{10.0};  ///< --rpe-length (repeatable): RPE segment lengths [m]
  double max_time_difference = 0.01;      ///< --max-dt: timestamp tolerance of the association [s]
  int threads = 0;                        ///< --threads: map distance threads, 0 = all cores
};

struct RegistrationBiasOptions {
  CommonOptions common;
  std::string log_path;
  std::string gt_path;   ///< --gt: the LiDAR's true trajectory (TUM)
  std::string csv_path;  ///< --csv: per-scan table; empty = none
  double from = 0.0;     ///< --from: seconds after the log's first scan
  double to = std::numeric_limits<double>::infinity();  ///< --to: same clock
  double max_time_difference = 0.01;                    ///< --max-dt: truth stamp tolerance [s]
  std::string storeys_path;  ///< --storeys: true storeys (storeys.yaml): split storeys / stairs
  std::string gt_imu_path;   ///< --gt-imu: the IMU's true trajectory (TUM): exact deskew
};

struct BenchOptions {
  std::string seeds = "1-30";  ///< --seeds: e.g. 1-30, 1,4,9, 1-10,1001-1010
  std::string out_dir;         ///< -o: one folder per seed, benchmark.md and .json
  int jobs = 0;                ///< --jobs: seeds at a time; 0 = the number of cores
  double max_duration = 0.0;   ///< --duration: simulate only this much of each walk [s]; 0 = all
  bool keep = false;           ///< --keep: keep bags, meshes and maps
  bool resume = false;         ///< --resume: keep the seeds an earlier bench into out_dir finished
  bool retry_failed = false;   ///< --retry-failed: with --resume, run the failed ones again
  std::string config;  ///< -c: configuration (YAML) every seed is mapped with; "" = defaults
};

struct BatchOptions {
  std::vector<std::string> inputs;  ///< logs, folders to search, manifests
  std::string out_dir;              ///< -o: FLEET_OUT
  std::string executor = "local";   ///< --executor: local or slurm
  int jobs = 0;                     ///< --jobs: local: logs at a time (0: cores / threads per run);
                                    ///< slurm: the array's %M (0: no limit)
  std::string config_path;          ///< -c/--config: base config of every log
  std::string calibration_path;     ///< --calibration: for logs without their own
  int retries = 1;                  ///< --retries: more attempts after a failed run
  bool only_failed = false;         ///< --only-failed: run only the logs whose last run failed
  bool force = false;               ///< --force: run every log again
  std::string status_dir;           ///< --status FLEET_OUT: report a batch, collect a Slurm one
  // Slurm (the command line wins over a manifest's slurm: section).
  bool submit_only = false;              ///< --submit-only: submit and return
  std::string partition, account;        ///< --partition, --account
  std::optional<int> cpus_per_task;      ///< --cpus-per-task
  std::string mem, time;                 ///< --mem, --time (sbatch syntax); empty = estimated
  std::vector<std::string> sbatch_args;  ///< --sbatch-arg (repeatable)
  std::string prolog;                    ///< --task-prolog: shell lines before storey in each task
  std::string storey_binary;             ///< --storey: the binary as the nodes see it
  double poll_seconds = 10.0;            ///< --poll: squeue interval [s]
};

struct RenderOptions {
  std::string out_dir;               ///< output folder of storey run
  std::string config_path;           ///< -c/--config: its `render:` section is used
  std::optional<int> keyframe;       ///< --keyframe: the keyframe view's keyframe
  std::string ground_truth;          ///< --gt: true trajectory (TUM)
  std::vector<std::string> compare;  ///< --compare: other run folders drawn with --gt
  std::optional<int> width, height;  ///< --width/--height [px]
  std::string views;                 ///< --views: comma-separated list; empty = config's
  std::optional<int> max_points;     ///< --max-points: map points drawn at most
};

struct StoreysOptions {
  std::string run_dir;      ///< output folder of storey run (map.ply, keyframes.tum)
  std::string out_dir;      ///< -o: where the new split goes (not the run folder)
  std::string config_path;  ///< -c/--config: its storeys: section is used
};

int runRun(const RunOptions& options);
int runInfo(const InfoOptions& options);
int runSimulate(const SimulateOptions& options);
int runEval(const EvalOptions& options);
int runRender(const RenderOptions& options);
int runStoreys(const StoreysOptions& options);
int runBench(const BenchOptions& options);
int runRegistrationBias(const RegistrationBiasOptions& options);
int runBatch(const BatchOptions& options);

}  // namespace storey::cli
