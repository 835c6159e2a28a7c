#include "config/config.h"

#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/yaml_section.h"
#include "io/calibration_file.h"
#include "io/sensor_yaml.h"

namespace storey {

namespace {

// One list of the plain keys of each section, shared by the reader and the
// writer (so default.yaml, the loader and configToYaml cannot disagree).
// V provides field(key, value) and section(key, visit_function).

template <typename V>
void visitInput(V& v, InputConfig& c) {
  v.field("points_topic", c.points_topic);
  v.field("imu_topic", c.imu_topic);
  v.field("min_range", c.min_range);
  v.field("max_range", c.max_range);
  v.field("imu_csv", c.imu_csv);
  v.field("imu_csv_time_offset", c.imu_csv_time_offset);
  v.field("velodyne_model", c.velodyne_model);
  v.field("velodyne_calibration", c.velodyne_calibration);
  v.field("velodyne_cut_angle_deg", c.velodyne_cut_angle_deg);
  v.field("pcap_clock", c.pcap_clock);
  v.field("pcap_data_port", c.pcap_data_port);
  v.field("pcap_position_port", c.pcap_position_port);
  v.field("imu_spike_gyro", c.imu_spike_gyro);
  v.field("imu_spike_accel", c.imu_spike_accel);
  v.field("imu_saturation_gyro", c.imu_saturation_gyro);
  v.field("imu_saturation_accel", c.imu_saturation_accel);
  v.field("lidar_occlusion_fraction", c.lidar_occlusion_fraction);
  v.field("read_ahead_scans", c.read_ahead_scans);
}

template <typename V>
void visitOdometry(V& v, OdometryConfig& c) {
  v.field("window_size", c.window_size);
  v.field("matching_rounds", c.matching_rounds);
  v.field("max_matched_planes", c.max_matched_planes);
  v.field("threads", c.threads);
  v.field("max_iterations", c.max_iterations);
  v.field("neighbours", c.neighbours);
  v.field("max_neighbour_distance", c.max_neighbour_distance);
  v.field("plane_fit_tolerance", c.plane_fit_tolerance);
  v.field("plane_fit_min_inliers", c.plane_fit_min_inliers);
  v.field("line_eigen_ratio", c.line_eigen_ratio);
  v.field("max_point_distance", c.max_point_distance);
  v.field("point_sigma", c.point_sigma);
  v.field("huber_threshold", c.huber_threshold);
  v.field("degenerate_translation_std", c.degenerate_translation_std);
  v.field("degenerate_rotation_std", c.degenerate_rotation_std);
  v.field("prior_velocity_sigma", c.prior_velocity_sigma);
  v.field("prior_gyro_bias_sigma", c.prior_gyro_bias_sigma);
  v.field("prior_accel_bias_sigma", c.prior_accel_bias_sigma);
  v.field("pose_sigma_translation", c.pose_sigma_translation);
  v.field("pose_sigma_rotation", c.pose_sigma_rotation);
  v.field("marginalise_pose", c.marginalise_pose);
  v.field("max_scan_gap", c.max_scan_gap);
  v.section("features", [&](auto& f) {
    FeatureConfig& fc = c.features;
    f.field("neighbours", fc.neighbours);
    f.field("sectors", fc.sectors);
    f.field("max_edges_per_sector", fc.max_edges_per_sector);
    f.field("edge_threshold", fc.edge_threshold);
    f.field("plane_threshold", fc.plane_threshold);
    f.field("occlusion_gap", fc.occlusion_gap);
    f.field("parallel_ratio", fc.parallel_ratio);
    f.field("max_gap_factor", fc.max_gap_factor);
    f.field("plane_voxel_size", fc.plane_voxel_size);
    f.field("edge_voxel_size", fc.edge_voxel_size);
  });
  v.section("local_map", [&](auto& m) {
    m.field("voxel_size", c.local_map.voxel_size);
    m.field("max_points_per_voxel", c.local_map.max_points_per_voxel);
    m.field("min_point_spacing", c.local_map.min_point_spacing);
    m.field("max_range", c.local_map.max_range);
  });
  v.section("imu_init", [&](auto& i) {
    ImuInitConfig& ic = c.imu_init;
    i.field("still_window", ic.still_window);
    i.field("max_gyro_std", ic.max_gyro_std);
    i.field("max_accel_std", ic.max_accel_std);
    i.field("noise_margin", ic.noise_margin);
    i.field("max_gyro_bias", ic.max_gyro_bias);
    i.field("max_gravity_error", ic.max_gravity_error);
    i.field("accel_bias_along_gravity", ic.accel_bias_along_gravity);
    i.field("motion_start", ic.motion_start);
    i.field("motion_window", ic.motion_window);
    i.field("motion_min_scans", ic.motion_min_scans);
  });
  v.section("preintegration", [&](auto& p) {
    p.field("repropagate_gyro_bias_change", c.preintegration.repropagate_gyro_bias_change);
    p.field("repropagate_accel_bias_change", c.preintegration.repropagate_accel_bias_change);
  });
}

template <typename V>
void visitBackend(V& v, BackendConfig& c) {
  v.field("srp", c.srp);
  v.field("queue_scans", c.queue_scans);
  v.section("keyframes", [&](auto& k) {
    k.field("distance", c.keyframes.distance);
    k.field("pitch_roll_deg", c.keyframes.pitch_roll_deg);
    k.field("max_interval", c.keyframes.max_interval);
  });
  v.section("extraction", [&](auto& e) {
    SrpExtractionConfig& x = c.extraction;
    e.field("min_points", x.min_points);
    e.field("max_srps", x.max_srps);
    e.field("explained_fraction", x.explained_fraction);
    e.field("max_detected_planes", x.max_detected_planes);
    e.field("orthogonal_tolerance_deg", x.orthogonal_tolerance_deg);
    e.field("ransac_distance", x.ransac_distance);
    e.field("ransac_iterations", x.ransac_iterations);
    e.field("voxel_size", x.voxel_size);
    e.field("ransac_max_points", x.ransac_max_points);
    e.field("min_range", x.min_range);
    e.field("max_range", x.max_range);
    e.field("max_points", x.max_points);
    e.field("min_extent", x.min_extent);
    e.field("min_view_angle_deg", x.min_view_angle_deg);
    e.field("point_sigma", x.point_sigma);
    e.field("max_effective_points", x.max_effective_points);
  });
  v.section("association", [&](auto& a) {
    AssociationConfig& x = c.association;
    a.field("angle_gate_deg", x.angle_gate_deg);
    a.field("distance_gate", x.distance_gate);
    a.field("mahalanobis_gate", x.mahalanobis_gate);
    a.field("pose_sigma_rotation", x.pose_sigma_rotation);
    a.field("pose_sigma_tilt", x.pose_sigma_tilt);
    a.field("pose_sigma_translation", x.pose_sigma_translation);
    a.field("plane_sigma_rotation", x.plane_sigma_rotation);
    a.field("plane_sigma_distance", x.plane_sigma_distance);
    a.field("ambiguity_margin", x.ambiguity_margin);
    a.field("new_plane_separation", x.new_plane_separation);
    a.field("confirmed_observations", x.confirmed_observations);
    a.field("max_rms_ratio", x.max_rms_ratio);
    a.field("track_distance", x.track_distance);
    a.field("track_gate", x.track_gate);
  });
  v.section("graph", [&](auto& g) {
    GraphConfig& x = c.graph;
    g.field("odometry_sigma_translation", x.odometry_sigma_translation);
    g.field("odometry_sigma_translation_per_m", x.odometry_sigma_translation_per_m);
    g.field("odometry_sigma_rotation", x.odometry_sigma_rotation);
    g.field("odometry_sigma_rotation_per_m", x.odometry_sigma_rotation_per_m);
    g.field("odometry_sigma_translation_per_rad", x.odometry_sigma_translation_per_rad);
    g.field("odometry_sigma_translation_per_m_climbed", x.odometry_sigma_translation_per_m_climbed);
    g.field("odometry_sigma_rotation_per_rad", x.odometry_sigma_rotation_per_rad);
    g.field("odometry_sigma_rotation_per_m_climbed", x.odometry_sigma_rotation_per_m_climbed);
    g.field("plane_sigma_rotation", x.plane_sigma_rotation);
    g.field("plane_sigma_distance", x.plane_sigma_distance);
    g.field("plane_loss_width", x.plane_loss_width);
    g.field("height_span_keyframes", x.height_span_keyframes);
    g.field("height_span_sigma", x.height_span_sigma);
    g.field("height_span_keyframe_frame", x.height_span_keyframe_frame);
    g.field("level_prior_sigma", x.level_prior_sigma);
    g.field("level_tolerance_deg", x.level_tolerance_deg);
    g.field("first_tilt_sigma", x.first_tilt_sigma);
    g.field("tilt_prior_sigma", x.tilt_prior_sigma);
    g.field("heading_frame_edges", x.heading_frame_edges);
    g.field("max_iterations", x.max_iterations);
    g.field("window_keyframes", x.window_keyframes);
    g.field("window_held_observations", x.window_held_observations);
    g.field("full_every", x.full_every);
    g.field("full_every_share", x.full_every_share);
    g.field("final_iterations", x.final_iterations);
    g.field("outlier_chi2", x.outlier_chi2);
    g.field("level_view_max_tilt_deg", x.level_view_max_tilt_deg);
  });
}

template <typename V>
void visitMap(V& v, MapConfig& c) {
  v.field("enabled", c.enabled);
  v.field("scan_spacing", c.scan_spacing);
  v.field("scan_angle_deg", c.scan_angle_deg);
  v.field("voxel_size", c.voxel_size);
  v.field("max_range", c.max_range);
  v.field("spill_to_disk", c.spill_to_disk);
  v.field("build_threads", c.build_threads);
  v.field("export_threads", c.export_threads);
}

template <typename V>
void visitStoreys(V& v, StoreysConfig& c) {
  v.field("enabled", c.enabled);
  v.field("voxel_size", c.voxel_size);
  v.field("normal_neighbours", c.normal_neighbours);
  v.field("plane_distance", c.plane_distance);
  v.field("plane_angle_deg", c.plane_angle_deg);
  v.field("min_region_area", c.min_region_area);
  v.field("horizontal_angle_deg", c.horizontal_angle_deg);
  v.field("slab_tolerance", c.slab_tolerance);
  v.field("min_floor_area", c.min_floor_area);
  v.field("min_storey_height", c.min_storey_height);
  v.field("floor_tolerance", c.floor_tolerance);
  v.field("min_clear_height", c.min_clear_height);
  v.field("max_clear_height", c.max_clear_height);
  v.field("stairs_cell_size", c.stairs_cell_size);
  v.field("stairs_min_rise", c.stairs_min_rise);
  v.field("stairs_trajectory_distance", c.stairs_trajectory_distance);
  v.field("footprint_alpha", c.footprint_alpha);
}

template <typename V>
void visitRender(V& v, RenderConfig& c) {
  v.field("enabled", c.enabled);
  v.field("width", c.width);
  v.field("height", c.height);
  v.section("views", [&](auto& w) {
    w.field("elevation", c.views.elevation);
    w.field("storeys", c.views.storeys);
    w.field("srp", c.views.srp);
    w.field("keyframe", c.views.keyframe);
    w.field("trajectories", c.views.trajectories);
  });
  v.field("max_display_points", c.max_display_points);
  v.field("point_size", c.point_size);
  v.field("line_width", c.line_width);
  v.field("keyframe", c.keyframe);
  v.field("keyframe_radius", c.keyframe_radius);
  v.field("srp_point_distance", c.srp_point_distance);
  v.field("ceiling_cut", c.ceiling_cut);
}

struct YamlReader {
  YamlSection& section_;
  template <typename T>
  void field(const char* key, T& value) {
    section_.read(key, value);
  }
  template <typename F>
  void section(const char* key, F visit) {
    YamlSection sub = section_.section(key);
    YamlReader reader{sub};
    visit(reader);
    sub.finish();
  }
};

struct YamlWriter {
  YAML::Emitter& out;
  template <typename T>
  void field(const char* key, const T& value) {
    out << YAML::Key << key << YAML::Value << value;
  }
  template <typename F>
  void section(const char* key, F visit) {
    out << YAML::Key << key << YAML::Value << YAML::BeginMap;
    visit(*this);
    out << YAML::EndMap;
  }
};

template <typename F>
void readSection(YamlSection& top, const char* key, F visit) {
  YamlReader reader{top};
  reader.section(key, visit);
}

void readSensor(YamlSection sensor, SensorConfig& config) {
  YamlSection pose = sensor.section("T_imu_lidar");
  if (sensor.has("T_imu_lidar")) config.T_imu_lidar = readPose(pose);
  sensor.read("time_offset_lidar_to_imu", config.time_offset_lidar_to_imu);
  YamlSection imu = sensor.section("imu");
  readImuNoise(imu, config.imu);
  YamlSection lidar = sensor.section("lidar");
  readLidarModel(lidar, "model", config.lidar_model);
  lidar.finish();
  sensor.finish();
}

}  // namespace

void applyConfigYaml(Config& config, const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = parseYaml(yaml_text, source);
  YamlSection top(root, source, "");
  Config result = config;  // all or nothing
  readSensor(top.section("sensor"), result.sensor);
  readSection(top, "input", [&](auto& v) { visitInput(v, result.input); });
  readSection(top, "odometry", [&](auto& v) { visitOdometry(v, result.odometry); });
  readSection(top, "backend", [&](auto& v) { visitBackend(v, result.backend); });
  readSection(top, "map", [&](auto& v) { visitMap(v, result.map); });
  readSection(top, "storeys", [&](auto& v) { visitStoreys(v, result.storeys); });
  readSection(top, "render", [&](auto& v) { visitRender(v, result.render); });
  top.finish();
  try {
    result.validate();
  } catch (const Error& e) {
    throw Error(source + ": " + e.what());
  }
  config = result;
}

std::string configToYaml(const Config& config) {
  Config copy = config;
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::BeginMap;
  out << YAML::Key << "sensor" << YAML::Value << YAML::BeginMap;
  out << YAML::Key << "T_imu_lidar" << YAML::Value;
  writePose(out, config.sensor.T_imu_lidar);
  out << YAML::Key << "time_offset_lidar_to_imu" << YAML::Value
      << config.sensor.time_offset_lidar_to_imu;
  out << YAML::Key << "imu" << YAML::Value;
  writeImuNoise(out, config.sensor.imu);
  out << YAML::Key << "lidar" << YAML::Value << YAML::BeginMap << YAML::Key << "model"
      << YAML::Value << toString(config.sensor.lidar_model) << YAML::EndMap;
  out << YAML::EndMap;
  YamlWriter writer{out};
  writer.section("input", [&](auto& v) { visitInput(v, copy.input); });
  writer.section("odometry", [&](auto& v) { visitOdometry(v, copy.odometry); });
  writer.section("backend", [&](auto& v) { visitBackend(v, copy.backend); });
  writer.section("map", [&](auto& v) { visitMap(v, copy.map); });
  writer.section("storeys", [&](auto& v) { visitStoreys(v, copy.storeys); });
  writer.section("render", [&](auto& v) { visitRender(v, copy.render); });
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

Config loadConfig(const std::string& path) {
  Config config;
  applyConfigYaml(config, readTextFile(path), path);
  return config;
}

void applyCalibrationFile(Config& config, const std::string& path) {
  const Calibration calibration = readCalibrationFile(path, calibrationOf(config));
  Config result = config;  // all or nothing: `config` is untouched on error
  result.sensor = calibration.sensor;
  result.input.points_topic = calibration.points_topic;
  result.input.imu_topic = calibration.imu_topic;
  result.input.velodyne_cut_angle_deg = calibration.velodyne_cut_angle_deg;
  try {
    result.validate();
  } catch (const Error& e) {
    throw Error(path + " (calibration): " + e.what());
  }
  config = result;
}

Config loadRunConfig(const std::string& config_path, const std::string& calibration_path) {
  Config config = config_path.empty() ? Config{} : loadConfig(config_path);
  if (!calibration_path.empty()) applyCalibrationFile(config, calibration_path);
  return config;
}

Calibration calibrationOf(const Config& config) {
  return {config.sensor, config.input.points_topic, config.input.imu_topic,
          config.input.velodyne_cut_angle_deg};
}

void Config::validate() const {
  input.validate();
  sensor.validate();
  odometry.validate();
  map.validate();
  backend.validate();
  storeys.validate();
  render.validate();
}

}  // namespace storey
