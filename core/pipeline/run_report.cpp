#include "pipeline/run_report.h"

#include <nlohmann/json.hpp>
#include <optional>

#include "common/statistics.h"
#include "common/version.h"
#include "export/storeys_json.h"
#include "trajectory/drift.h"

namespace storey {

struct RunReportBuilder::Data {
  Config config;
  nlohmann::json input, initialisation, drift, time_offset;
  nlohmann::json faults = nlohmann::json::object();
  double wall_seconds = 0.0;
  double log_seconds = 0.0;
  std::int64_t scans = 0;
  std::vector<double> ms_preintegration, ms_deskew, ms_features, ms_matching, ms_optimisation,
      ms_total, cpu_ms_total, edges, planes, plane_matches, line_matches, iterations;
  std::array<std::int64_t, static_cast<std::size_t>(FeatureReject::kCount)> feature_rejects{};
  std::array<std::int64_t, static_cast<std::size_t>(MatchReject::kCount)> match_rejects{};
  std::int64_t degenerate_scans = 0;
  std::int64_t degenerate_translation_directions = 0;
  std::int64_t degenerate_rotation_directions = 0;
  std::optional<BackendStats> backend;
  std::optional<nlohmann::json> map, storeys;
  std::optional<double> wall_seconds_total;
  nlohmann::json peak_memory = nlohmann::json::object();
  std::optional<std::vector<std::string>> files;
  std::vector<std::string> warnings;
  std::size_t warning_count = 0;
};

RunReportBuilder::RunReportBuilder(const Config& config) : data_(std::make_unique<Data>()) {
  data_->config = config;
}
RunReportBuilder::~RunReportBuilder() = default;

void RunReportBuilder::addScan(const OdometryResult& scan) {
  Data& d = *data_;
  const OdometryScanStats& s = scan.stats;
  ++d.scans;
  d.ms_preintegration.push_back(s.ms_preintegration);
  d.ms_deskew.push_back(s.ms_deskew);
  d.ms_features.push_back(s.ms_features);
  d.ms_matching.push_back(s.ms_matching);
  d.ms_optimisation.push_back(s.ms_optimisation);
  d.ms_total.push_back(s.ms_total);
  d.cpu_ms_total.push_back(s.cpu_ms_total);
  d.edges.push_back(static_cast<double>(s.edge_features));
  d.planes.push_back(static_cast<double>(s.plane_features));
  d.plane_matches.push_back(static_cast<double>(s.plane_matches));
  d.line_matches.push_back(static_cast<double>(s.line_matches));
  d.iterations.push_back(s.solver_iterations);
  for (std::size_t i = 0; i < d.feature_rejects.size(); ++i)
    d.feature_rejects[i] += s.feature_rejects[i];
  for (std::size_t i = 0; i < d.match_rejects.size(); ++i) d.match_rejects[i] += s.match_rejects[i];
  if (s.degenerate_translation_directions > 0 || s.degenerate_rotation_directions > 0)
    ++d.degenerate_scans;
  d.degenerate_translation_directions += s.degenerate_translation_directions;
  d.degenerate_rotation_directions += s.degenerate_rotation_directions;
}

void RunReportBuilder::setInput(const std::string& log_path, const LogReadStats& stats,
                                const OdometryDrops& drops) {
  nlohmann::json dropped = nlohmann::json::object();
  for (const auto& [reason, count] : stats.dropped) dropped[reason] = count;
  data_->input = {{"log", log_path},
                  {"scans_read", stats.scans},
                  {"imu_samples_read", stats.imu_samples},
                  {"points_read", stats.points},
                  {"dropped_by_reader", dropped},
                  {"reordered_by_reader", stats.reordered},
                  {"scans_not_processed",
                   {{"before_first_imu_sample", drops.before_first_imu},
                    {"after_last_imu_sample", drops.after_last_imu},
                    {"empty", drops.empty}}}};
}

void RunReportBuilder::setFaults(const FaultLog& faults) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& [kind, summary] : faults.kinds()) {
    nlohmann::json events = nlohmann::json::array();
    for (const FaultEvent& e : summary.first)
      events.push_back({{"time_s", e.time}, {"duration_s", e.duration}, {"detail", e.detail}});
    out[kind] = {
        {"count", summary.count}, {"total_duration_s", summary.total_duration}, {"events", events}};
  }
  data_->faults = out;
}

void RunReportBuilder::setInitialisation(const ImuState& s, const OdometryInitialisation& how) {
  const Eigen::Vector3d up_imu = s.T_world_imu.rotation().conjugate() * Eigen::Vector3d::UnitZ();
  data_->initialisation = {
      {"start", how.in_motion ? "moving" : "still"},
      {"gyro_bias_rad_s", {s.bias.gyro.x(), s.bias.gyro.y(), s.bias.gyro.z()}},
      {"accel_bias_m_s2", {s.bias.accel.x(), s.bias.accel.y(), s.bias.accel.z()}},
      {"up_in_imu_frame", {up_imu.x(), up_imu.y(), up_imu.z()}}};
  if (how.in_motion) {
    const MotionInitStats& m = how.motion;
    data_->initialisation["not_still"] = how.not_still;
    data_->initialisation["moving"] = {{"scans", m.scans},
                                       {"window_s", m.window_s},
                                       {"speed_m_s", m.speed_start},
                                       {"vertical_speed_m_s", m.vertical_speed_start},
                                       {"path_length_m", m.path_length},
                                       {"gravity_found_m_s2", m.gravity_norm},
                                       {"position_rms_m", m.position_rms},
                                       {"min_matches", m.min_matches},
                                       {"velocity_sigma_m_s", m.velocity_sigma},
                                       {"tilt_sigma_rad", m.tilt_sigma},
                                       {"gyro_bias_sigma_rad_s", m.gyro_bias_sigma}};
  }
}

void RunReportBuilder::setTimeOffset(const TimeOffsetEstimate& t, double configured_s) {
  data_->time_offset = {{"configured_s", configured_s},
                        {"scan_pairs", t.pairs},
                        {"rotation_rate_change_rms_rad_s", t.excitation},
                        {"detected", t.detected()}};
  if (t.valid()) {
    data_->time_offset["offset_s"] = t.offset_s;
    data_->time_offset["sigma_s"] = t.sigma_s;
  }
}

void RunReportBuilder::setTrajectory(const Trajectory& trajectory) {
  const EndPointDrift d = endPointDrift(trajectory);
  data_->drift = {{"dX_m", d.dx},
                  {"dY_m", d.dy},
                  {"dZ_m", d.dz},
                  {"dXYZ_m", d.dxyz},
                  {"dYaw_rad", d.dyaw},
                  {"dPitch_rad", d.dpitch},
                  {"dRoll_rad", d.droll},
                  {"dAngle_rad", d.dangle},
                  {"path_length_m", d.path_length},
                  {"dXYZ_percent_of_path", d.percent_of_path()}};
  if (trajectory.size() >= 2) data_->log_seconds = trajectory.back().time - trajectory.front().time;
}

void RunReportBuilder::setWallTime(double seconds) {
  data_->wall_seconds = seconds;
}

void RunReportBuilder::setBackend(const BackendStats& stats) {
  data_->backend = stats;
}

void RunReportBuilder::setMap(const MapStage& o) {
  const StoreySegmentationStats& s = o.storeys.stats;
  data_->map = nlohmann::json{
      {"points", o.map ? o.map->size() : 0},
      {"voxel_size_m", o.voxel_size},
      {"keyframes", o.build.scans},  // map scans (the key keeps its first name)
      {"keyframe_points", o.build.points_in},
      {"keyframe_points_stored", o.build.points_stored},
      {"left_out",
       {{"beyond_range", o.build.points_beyond_range}, {"non_finite", o.build.points_non_finite}}},
      {"segmentation",
       {{"subsampled_points", s.subsampled_points},
        {"planar_regions", s.regions},
        {"floor_candidates", s.floor_candidates},
        {"ceiling_candidates", s.ceiling_candidates},
        {"floor_slabs", s.floor_slabs},
        {"slabs_rejected",
         {{"smaller_than_min_floor_area", s.slabs_too_small},
          {"within_min_storey_height_of_a_kept_floor", s.slabs_too_close}}},
        {"stair_cells", s.stair_cells},
        {"flight_ends", s.flight_ends},
        {"flight_ends_on_a_floor", s.flight_ends_on_floor},
        {"usual_sensor_height_m", s.usual_sensor_height}}},
      {"files", o.files},
      {"seconds",
       {{"build", o.seconds_build},
        {"storeys", o.seconds_storeys},
        {"normals", s.seconds_normals},
        {"regions", s.seconds_regions},
        {"footprints", s.seconds_footprints},
        {"export", o.seconds_export}}}};
  data_->peak_memory["map_build"] = o.peak_mib_after_build;
  data_->peak_memory["storeys"] = o.peak_mib_after_storeys;
  data_->peak_memory["export"] = o.peak_mib_after_export;
  nlohmann::json table = storeyTableJson(o.storeys.storeys);
  for (nlohmann::json& entry : table) entry.erase("footprint");  // in storeys.json
  data_->storeys = table;
}

void RunReportBuilder::setStreamingPeakMemory(double mib) {
  data_->peak_memory["streaming"] = mib;
}

void RunReportBuilder::setTotalWallTime(double seconds) {
  data_->wall_seconds_total = seconds;
}

void RunReportBuilder::setFiles(const std::vector<std::string>& files) {
  data_->files = files;
}

void RunReportBuilder::setWarnings(const std::vector<std::string>& warnings, std::size_t count) {
  data_->warnings = warnings;
  data_->warning_count = count;
}

namespace {

nlohmann::json summary(const std::vector<double>& samples) {
  return {{"median", quantile(samples, 0.5)},
          {"p95", quantile(samples, 0.95)},
          {"mean", mean(samples)},
          {"max", quantile(samples, 1.0)}};
}

nlohmann::json meanMedian(const std::vector<double>& samples) {
  return {{"mean", mean(samples)}, {"median", quantile(samples, 0.5)}, {"count", samples.size()}};
}

// The back end's section: keyframes, planes, association outcomes (and why
// pairs failed the gates), wrong associations, timings per keyframe.
nlohmann::json backendJson(const Config& config, const std::optional<BackendStats>& stats) {
  if (!config.backend.srp || !stats) {
    return {{"srp_requested", config.backend.srp},
            {"status", "switched off (--no-srp): trajectory.tum is the odometry"}};
  }
  const BackendStats& b = *stats;
  nlohmann::json outcomes = nlohmann::json::object();
  for (std::size_t i = 0; i < b.outcomes.size(); ++i)
    outcomes[backend::toString(static_cast<backend::AssociationOutcome>(i))] = b.outcomes[i];
  nlohmann::json gates = nlohmann::json::object();
  for (std::size_t i = 0; i < b.gate_rejects.size(); ++i)
    gates[backend::toString(static_cast<backend::GateReject>(i))] = b.gate_rejects[i];
  nlohmann::json planes = nlohmann::json::object();
  for (std::size_t i = 0; i < b.plane_rejects.size(); ++i)
    planes[backend::toString(static_cast<backend::PlaneReject>(i))] = b.plane_rejects[i];
  std::vector<double> graph_sizes(b.optimisation_keyframes.begin(), b.optimisation_keyframes.end());
  return {{"srp_requested", true},
          {"status", "on: trajectory.tum is the optimised trajectory"},
          {"scans", b.scans},
          {"keyframes", b.keyframes},
          {"srps", b.srps},
          {"keyframes_without_srp", b.keyframes_without_srp},
          {"planes", b.planes},
          {"plane_observations", b.observations},
          {"association",
           {{"outcomes", outcomes},
            {"rejected_pairs_by_gate", gates},
            {"srp_fit_rms_median_m", b.srp_rms_median},
            {"rough_fit_meaning",
             "SRPs whose fit RMS exceeds association.max_rms_ratio times the median fit RMS "
             "of the SRPs before them: not used"},
            {"wrong_associations", b.wrong_associations},
            {"wrong_associations_meaning",
             "observations whose residual after the end's whole-graph solve exceeds "
             "graph.outlier_chi2: left out of one more whole-graph solve"},
            {"tilted_level_views", b.tilted_level_views},
            {"tilted_level_views_meaning",
             "views of a floor or ceiling tilted by more than graph.level_view_max_tilt_deg "
             "under the solved poses: left out of the end's whole-graph solve (counted among "
             "wrong_associations too)"}}},
          {"detected_planes_not_srp", planes},
          {"optimisations", b.optimisations},
          {"full_optimisations", b.full_optimisations},
          {"planes_seen_again_after_a_window", b.revisits},
          {"timing_ms_per_keyframe",
           {{"srp_extraction", summary(b.ms_extraction)},
            {"association", summary(b.ms_association)},
            {"optimisation", summary(b.ms_optimisation)},
            {"optimisation_newest_keyframes", summary(b.ms_window_optimisation)},
            {"optimisation_whole_graph", summary(b.ms_full_optimisation)},
            {"final_optimisation", b.ms_final_optimisation},
            {"total", summary(b.ms_keyframe)},
            {"total_cpu", summary(b.cpu_ms_keyframe)}}},
          {"keyframes_in_graph_at_optimisation", summary(graph_sizes)}};
}

// The paper's Table II: mean (and median) running time of each component [ms].
nlohmann::json tableTwo(const std::vector<double>& ms_odometry,
                        const std::optional<BackendStats>& b) {
  nlohmann::json t = {{"lidar_inertial_odometry_per_scan", meanMedian(ms_odometry)}};
  if (b) {
    t["srp_extraction_per_keyframe"] = meanMedian(b->ms_extraction);
    t["find_global_constraint_per_keyframe"] = meanMedian(b->ms_association);
    t["backend_optimisation_per_optimised_keyframe"] = meanMedian(b->ms_optimisation);
  }
  return t;
}

}  // namespace

nlohmann::json RunReportBuilder::json() const {
  const Data& d = *data_;
  nlohmann::json feature_rejects = nlohmann::json::object();
  for (std::size_t i = 0; i < d.feature_rejects.size(); ++i)
    feature_rejects[toString(static_cast<FeatureReject>(i))] = d.feature_rejects[i];
  nlohmann::json match_rejects = nlohmann::json::object();
  for (std::size_t i = 0; i < d.match_rejects.size(); ++i)
    match_rejects[toString(static_cast<MatchReject>(i))] = d.match_rejects[i];
  nlohmann::json report;
  report["storey_version"] = storeyVersion();
  report["input"] = d.input;
  report["faults"] = d.faults;
  report["imu_initialisation"] = d.initialisation;
  if (!d.time_offset.is_null()) report["time_offset"] = d.time_offset;
  report["odometry"] = {
      {"scans", d.scans},
      {"timing_ms",
       {{"preintegration", summary(d.ms_preintegration)},
        {"deskew", summary(d.ms_deskew)},
        {"features", summary(d.ms_features)},
        {"matching", summary(d.ms_matching)},
        {"optimisation", summary(d.ms_optimisation)},
        {"total_per_scan", summary(d.ms_total)},
        {"total_per_scan_cpu", summary(d.cpu_ms_total)}}},
      {"features_per_scan", {{"edges", summary(d.edges)}, {"planes", summary(d.planes)}}},
      {"matches_per_scan",
       {{"point_to_plane", summary(d.plane_matches)}, {"point_to_line", summary(d.line_matches)}}},
      {"rejected_feature_points", feature_rejects},
      {"rejected_matches", match_rejects},
      {"degenerate_scans", d.degenerate_scans},
      {"degenerate_directions",
       {{"translation", d.degenerate_translation_directions},
        {"rotation", d.degenerate_rotation_directions}}},
      {"solver_iterations_per_scan", summary(d.iterations)}};
  report["backend"] = backendJson(d.config, d.backend);
  report["table_ii_mean_median_ms"] = tableTwo(d.ms_total, d.backend);
  report["end_point_drift"] = d.drift;
  report["log_duration_s"] = d.log_seconds;
  report["wall_time_s"] = d.wall_seconds;
  report["real_time_factor"] = d.wall_seconds > 0 ? d.log_seconds / d.wall_seconds : 0.0;
  if (d.map) report["map"] = *d.map;
  if (d.storeys) report["storeys"] = *d.storeys;
  if (d.wall_seconds_total) report["wall_time_s_total"] = *d.wall_seconds_total;
  // The process's peak resident size [MiB] at the end of each stage (it only
  // grows: the stage that raised it is the one whose figure first reaches the last).
  if (!d.peak_memory.empty()) report["peak_memory_mib_after"] = d.peak_memory;
  if (d.files) report["files"] = *d.files;
  report["warning_count"] = d.warning_count;
  report["warnings"] = d.warnings;
  if (d.warning_count > d.warnings.size())
    report["warnings"].push_back(std::to_string(d.warning_count - d.warnings.size()) +
                                 " more warnings not listed");
  return report;
}

}  // namespace storey
