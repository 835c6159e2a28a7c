#pragma once
/// The table of `storey bench`: one row per seed (the building, the sensors,
/// the walk, and what Storey made of it) and the distribution of each figure
/// over the seeds. Read from each seed's folder: sim/spec.yaml, run/report.json,
/// eval.json. No process handling here (cmd_bench.cpp), so it can be tested.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace storey::cli {

struct BenchRow {
  std::uint64_t seed = 0;
  std::string error;  ///< empty when every step succeeded
  // The drawn building, rig and walk (spec.yaml).
  int storeys = 0;
  int wings = 0;
  double min_storey_height = 0.0, max_storey_height = 0.0;  ///< [m]
  double stair_slope_deg = 0.0;
  std::string stairs = "switchback";  ///< the stairs' kind, "wide" when 4 m or more
  std::string lidar;
  double lidar_tilt_deg = 0.0;  ///< angle between the LiDAR's axis and the body's up axis
  double imu_rate_hz = 0.0;
  std::string imu_grade = "custom";  ///< tactical, consumer or custom
  std::string motion = "legged";
  /// The plan's special parts: "L", "T" or "U" (arms), "split level",
  /// "single-loaded", "atrium N" (rooms), "walls D" (partition angle [deg]
  /// when not 90), "N rooms entered"; empty for a plain corridor building.
  std::string features;
  // The run and its evaluation.
  std::optional<double> path_m, duration_s;
  std::optional<double> ate_m;            ///< ATE RMSE after SE(3) alignment [m]
  std::optional<double> ate_unaligned_m;  ///< ATE RMSE without alignment [m]
  std::optional<double> odometry_ate_m;   ///< ATE RMSE of the front end alone, SE(3) [m]
  std::optional<double> end_drift_m;      ///< end-point drift |dXYZ| [m]
  std::optional<double> worst_floor_m;    ///< largest |floor elevation error| [m]
  std::optional<double> worst_height_m;   ///< largest |floor-to-floor height error| [m]
  std::optional<int> storeys_found;
  std::optional<double> map_median_m;  ///< map-to-mesh median distance [m]
  /// Plane observations of the back end on another surface than their plane's
  /// (checked with the true poses) and not down-weighted by its robust loss.
  std::optional<double> wrong_matches;
  std::optional<double> real_time_factor;  ///< log seconds per wall second of `storey run`
  std::optional<double> peak_memory_mb;    ///< of `storey run` [MB]
};

/// Fills the row's figures from a seed folder's files; a missing or
/// unreadable file leaves its figures empty and sets `error` when none is set.
void readBenchRow(const std::string& seed_dir, BenchRow& row);

/// Largest |(e_{k+1} - e_k)| over consecutive true storeys both matched, from
/// eval.json's storeys list (true_index, error_m); nullopt without two.
std::optional<double> worstStoreyHeightError(const std::vector<std::pair<int, double>>& errors);

/// Median, 90th percentile and worst of a column ("worst" = max, or min when
/// `higher_is_better`); empty values are left out.
struct Distribution {
  std::size_t count = 0;
  double median = 0.0, p90 = 0.0, worst = 0.0;
};
Distribution distributionOf(const std::vector<std::optional<double>>& values,
                            bool higher_is_better = false);

/// What a finished seed leaves in its folder as seed.json: the parts of its row
/// that its own files do not hold (peak memory, the failed step's error), the
/// --duration and the configuration's text (-c; "" = defaults) it ran with, so
/// that `storey bench --resume` can keep the seed.
std::string seedRecordJson(const BenchRow& row, double max_duration, const std::string& config);

/// Reads a seed folder that a finished seed left: true, and `row` filled as
/// readBenchRow does plus the record's peak memory and error, when
/// seed_dir/seed.json is that seed's record written with the same
/// `max_duration` and `config` (a record without one ran with the defaults);
/// false (row untouched) otherwise.
bool readSeedRecord(const std::string& seed_dir, std::uint64_t seed, double max_duration,
                    const std::string& config, BenchRow& row);

std::string benchMarkdown(const std::vector<BenchRow>& rows, const std::string& title);
std::string benchJson(const std::vector<BenchRow>& rows);

}  // namespace storey::cli
