#include "sim/building_spec.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "common/error.h"
#include "common/yaml_section.h"
#include "sim/embedded_presets.h"
#include "sim/lidar_model.h"
#include "sim/random_spec.h"

namespace storey::sim {
namespace {

constexpr double kDegToRad = M_PI / 180.0;

void readDegrees(YamlSection& s, const std::string& key, double& radians) {
  double degrees = radians / kDegToRad;
  s.read(key, degrees);
  radians = degrees * kDegToRad;
}

/// {translation: [x y z], rotation_rpy_deg: [roll pitch yaw]} or rotation_xyzw.
void readMount(YamlSection& parent, const std::string& key, Pose& pose) {
  if (!parent.has(key)) {
    parent.section(key);  // mark known
    return;
  }
  YamlSection s = parent.section(key);
  Eigen::Vector3d t = pose.translation();
  s.read("translation", t);
  Eigen::Quaterniond q = pose.rotation();
  if (s.has("rotation_rpy_deg") && s.has("rotation_xyzw"))
    s.fail("rotation_xyzw", "cannot be given together with rotation_rpy_deg");
  if (s.has("rotation_rpy_deg")) {
    Eigen::Vector3d rpy;
    s.read("rotation_rpy_deg", rpy);
    rpy *= kDegToRad;
    q = Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
        Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
        Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX());
  } else {
    s.section("rotation_rpy_deg");  // absent: only marks the key known
  }
  if (s.has("rotation_xyzw")) {
    std::vector<double> v;
    s.read("rotation_xyzw", v, 4);
    const Eigen::Quaterniond raw(v[3], v[0], v[1], v[2]);
    if (std::abs(raw.norm() - 1.0) > 1e-3)
      s.fail("rotation_xyzw", "must be a unit quaternion (x y z w)");
    q = raw.normalized();
  } else {
    s.section("rotation_xyzw");
  }
  s.finish();
  pose = Pose(q, t);
}

// Named values: the text of each, and back (storey::Error for an unknown name).
std::string nameOf(LidarModel model) {
  return toString(model);
}
void parseName(const std::string& name, LidarModel& model) {
  LidarModel parsed = LidarModel::kGeneric;
  try {
    parsed = lidarModelFromString(name);
  } catch (const Error&) {
  }
  if (!isSimulatedLidar(parsed)) {
    throw Error(std::string("must be one of the simulated LiDARs (") + simulatedLidarNames() +
                "), got '" + name + "'");
  }
  model = parsed;
}
std::string nameOf(StairKind kind) {
  return toString(kind);
}
void parseName(const std::string& name, StairKind& kind) {
  kind = stairKindFromString(name);
}
std::string nameOf(RobotMotion motion) {
  return toString(motion);
}
void parseName(const std::string& name, RobotMotion& motion) {
  motion = robotMotionFromString(name);
}
constexpr const char* kCustomGrade = "custom";
std::string nameOf(const std::optional<ImuGrade>& grade) {
  return grade ? toString(*grade) : kCustomGrade;
}
void parseName(const std::string& name, std::optional<ImuGrade>& grade) {
  grade.reset();
  if (name != kCustomGrade) grade = imuGradeFromString(name);
}

// One field list per part of the spec, shared by the reader and the writer
// (so spec.yaml, written by `storey simulate`, reads back as the same spec).
// V provides field(key, value), degrees(key, radians), mount(key, pose),
// list(key, doubles), section(key, visit), choice(key, named value) and
// preset(key, named value, apply): a named value whose apply(value) sets the
// defaults of the section's other keys, so it comes first in its section.

template <typename V>
void visitStairwell(V& v, StairwellSpec& s) {
  v.choice("kind", s.kind);
  v.field("width", s.width);
  v.field("riser", s.riser);
  v.field("tread", s.tread);
  v.field("floor_landing_depth", s.floor_landing_depth);
  v.field("half_landing_depth", s.half_landing_depth);
  v.field("position", s.position);
}

template <typename V>
void visitLayout(V& v, BuildingLayoutSpec& b) {
  v.list("storey_heights", b.storey_heights);
  v.field("slab_thickness", b.slab_thickness);
  v.field("wall_thickness", b.wall_thickness);
  v.field("corridor_length", b.corridor_length);
  v.field("corridor_width", b.corridor_width);
  v.field("room_depth", b.room_depth);
  v.field("room_width", b.room_width);
  v.field("wings", b.wings);
  v.field("single_loaded", b.single_loaded);
  v.field("door_width", b.door_width);
  v.field("door_height", b.door_height);
  v.field("window_width", b.window_width);
  v.field("window_sill", b.window_sill);
  v.field("window_height", b.window_height);
  v.field("glass_front_fraction", b.glass_front_fraction);
  v.field("clutter_density", b.clutter_density);
  v.field("pillar_spacing", b.pillar_spacing);
  v.degrees("partition_angle_deg", b.partition_angle);
  v.section("stairwell", [&](auto& w) { visitStairwell(w, b.stairwell); });
  v.section("atrium", [&](auto& a) {
    a.field("rooms", b.atrium.rooms);
    a.field("position", b.atrium.position);
    a.field("glass_balustrade", b.atrium.glass_balustrade);
    a.field("balustrade_height", b.atrium.balustrade_height);
  });
  v.section("arms", [&](auto& a) {
    a.list("positions", b.arms.positions, true);
    a.list("lengths", b.arms.lengths, true);
    a.list("rises", b.arms.rises, true);
  });
}

template <typename V>
void visitRobot(V& v, RobotSpec& r) {
  v.preset("motion", r.motion, [&](RobotMotion m) { r = robotForMotion(m); });
  v.field("walk_speed", r.walk_speed);
  v.field("stair_speed", r.stair_speed);
  v.field("max_accel", r.max_accel);
  v.field("max_lateral_accel", r.max_lateral_accel);
  v.degrees("max_yaw_rate_deg", r.max_yaw_rate);
  v.field("turn_radius", r.turn_radius);
  v.field("body_height", r.body_height);
  v.field("lane_offset", r.lane_offset);
  v.field("still_time", r.still_time);
  v.field("start_offset", r.start_offset);
  v.field("rooms_entered", r.rooms_entered);
  v.field("rounds", r.rounds);
  v.section("gait", [&](auto& g) {
    g.field("frequency_hz", r.gait.frequency);
    g.field("bounce", r.gait.bounce);
    g.degrees("roll_deg", r.gait.roll);
    g.degrees("pitch_deg", r.gait.pitch);
  });
  v.section("handheld_gait", [&](auto& g) {
    g.field("frequency_hz", r.handheld_gait.frequency);
    g.field("bounce", r.handheld_gait.bounce);
    g.field("sway", r.handheld_gait.sway);
    g.degrees("roll_deg", r.handheld_gait.roll);
    g.degrees("pitch_deg", r.handheld_gait.pitch);
    g.degrees("yaw_deg", r.handheld_gait.yaw);
    g.field("slope_pitch", r.handheld_gait.slope_pitch);
  });
}

template <typename V>
void visitSensors(V& v, SensorsSpec& s) {
  v.mount("T_body_lidar", s.T_body_lidar);
  v.mount("T_body_imu", s.T_body_imu);
  v.field("start_time", s.start_time);
  v.field("points_topic", s.points_topic);
  v.field("imu_topic", s.imu_topic);
  v.field("lidar_frame_id", s.lidar_frame_id);
  v.field("imu_frame_id", s.imu_frame_id);
  v.section("lidar", [&](auto& l) {
    l.choice("model", s.lidar.model);
    l.field("rotation_rate_hz", s.lidar.rotation_rate);
    l.field("range_noise", s.lidar.range_noise);
    l.field("dropout", s.lidar.dropout);
    l.field("min_range", s.lidar.min_range);
    l.field("max_range", s.lidar.max_range);
    l.field("intensity_noise", s.lidar.intensity_noise);
  });
  v.section("imu", [&](auto& i) {
    i.preset("grade", s.imu.grade, [&](const std::optional<ImuGrade>& g) {
      if (g) s.imu = imuGrade(*g, imuGradeRates(*g).max_hz);
    });
    i.field("rate_hz", s.imu.rate);
    i.field("gyro_noise_density", s.imu.gyro_noise_density);
    i.field("accel_noise_density", s.imu.accel_noise_density);
    i.field("gyro_random_walk", s.imu.gyro_random_walk);
    i.field("accel_random_walk", s.imu.accel_random_walk);
    i.field("gravity", s.imu.gravity);
    i.field("gyro_bias", s.imu.gyro_bias);
    i.field("accel_bias", s.imu.accel_bias);
    i.field("orientation", s.imu.orientation);
    i.degrees("orientation_sigma_deg", s.imu.orientation_sigma);
  });
}

template <typename V>
void visitSpec(V& v, BuildingSpec& spec) {
  v.section("building", [&](auto& b) { visitLayout(b, spec.building); });
  v.section("robot", [&](auto& r) { visitRobot(r, spec.robot); });
  v.section("sensors", [&](auto& s) { visitSensors(s, spec.sensors); });
}

struct SpecReader {
  YamlSection& s;
  template <typename T>
  void field(const char* key, T& value) {
    s.read(key, value);
  }
  void degrees(const char* key, double& radians) { readDegrees(s, key, radians); }
  void degrees(const char* key, Eigen::Vector3d& radians) {
    Eigen::Vector3d degrees = radians / kDegToRad;
    s.read(key, degrees);
    radians = degrees * kDegToRad;
  }
  void mount(const char* key, Pose& pose) { readMount(s, key, pose); }
  template <typename T>
  void choice(const char* key, T& value) {
    std::string name = nameOf(value);
    s.read(key, name);
    if (!s.has(key)) return;
    try {
      parseName(name, value);
    } catch (const Error& e) {
      s.fail(key, e.what());
    }
  }
  template <typename T, typename F>
  void preset(const char* key, T& value, F apply) {
    choice(key, value);
    if (!s.has(key)) return;
    try {
      apply(T(value));
    } catch (const Error& e) {
      s.fail(key, e.what());
    }
  }
  void list(const char* key, std::vector<double>& values, bool may_be_empty = false) {
    if (!s.has(key)) {
      s.section(key);  // mark known
      return;
    }
    std::vector<double> read;
    s.readList(key, read);
    if (read.empty() && !may_be_empty) s.fail(key, "must be a non-empty list of numbers");
    values = std::move(read);
  }
  template <typename F>
  void section(const char* key, F visit) {
    YamlSection sub = s.section(key);
    SpecReader reader{sub};
    visit(reader);
    sub.finish();
  }
};

/// The shortest decimal text that reads back as exactly `v` (0.341, not 0.34100000000000003).
std::string shortest(double v) {
  char text[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(text, sizeof(text), "%.*g", digits, v);
    if (std::strtod(text, nullptr) != v) continue;
    // Whole and large numbers without an exponent (10, not 1e+01).
    if (std::abs(v) >= 1.0 && std::abs(v) < 1e16 && std::strchr(text, 'e') != nullptr) {
      const int integer_digits = static_cast<int>(std::floor(std::log10(std::abs(v)))) + 1;
      std::snprintf(text, sizeof(text), "%.*f", std::max(0, digits - integer_digits), v);
    }
    break;
  }
  return text;
}

struct SpecWriter {
  YAML::Emitter& out;
  template <typename T>
  void field(const char* key, const T& value) {
    out << YAML::Key << key << YAML::Value << value;
  }
  void field(const char* key, double value) {
    out << YAML::Key << key << YAML::Value << shortest(value);
  }
  void field(const char* key, const Eigen::Vector3d& v) { list(key, {v.x(), v.y(), v.z()}); }
  void degrees(const char* key, double radians) { field(key, radians / kDegToRad); }
  void degrees(const char* key, const Eigen::Vector3d& radians) {
    field(key, Eigen::Vector3d(radians / kDegToRad));
  }
  template <typename T>
  void choice(const char* key, const T& value) {
    field(key, nameOf(value));
  }
  template <typename T, typename F>
  void preset(const char* key, const T& value, F) {
    choice(key, value);
  }
  void mount(const char* key, const Pose& pose) {
    const Eigen::Quaterniond& q = pose.rotation();
    out << YAML::Key << key << YAML::Value << YAML::BeginMap;
    field("translation", pose.translation());
    list("rotation_xyzw", {q.x(), q.y(), q.z(), q.w()});
    out << YAML::EndMap;
  }
  void list(const char* key, const std::vector<double>& values, bool /*may_be_empty*/ = false) {
    out << YAML::Key << key << YAML::Value << YAML::Flow << YAML::BeginSeq;
    for (double v : values) out << shortest(v);
    out << YAML::EndSeq;
  }
  template <typename F>
  void section(const char* key, F visit) {
    out << YAML::Key << key << YAML::Value << YAML::BeginMap;
    visit(*this);
    out << YAML::EndMap;
  }
};

std::string numberText(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

void check(bool ok, const BuildingSpec& spec, const std::string& key, const std::string& what) {
  if (!ok) throw Error(spec.source + ": key '" + key + "' " + what);
}

}  // namespace

const char* toString(StairKind kind) {
  switch (kind) {
    case StairKind::kSwitchback:
      return "switchback";
    case StairKind::kStraight:
      return "straight";
    case StairKind::kLShaped:
      return "l_shaped";
  }
  return "switchback";
}

StairKind stairKindFromString(const std::string& name) {
  for (StairKind kind : {StairKind::kSwitchback, StairKind::kStraight, StairKind::kLShaped})
    if (name == toString(kind)) return kind;
  throw Error("unknown stair kind '" + name + "' (switchback, straight or l_shaped)");
}

void BuildingSpec::validate() const {
  const BuildingLayoutSpec& b = building;
  check(!b.storey_heights.empty(), *this, "building.storey_heights",
        "must list at least one storey");
  for (double h : b.storey_heights)
    check(h >= 2.4 && h <= 8.0, *this, "building.storey_heights", "values must be in [2.4, 8] m");
  check(b.slab_thickness >= 0.05 && b.slab_thickness <= 1.0, *this, "building.slab_thickness",
        "must be in [0.05, 1] m");
  check(b.wall_thickness >= 0.05 && b.wall_thickness <= 0.6, *this, "building.wall_thickness",
        "must be in [0.05, 0.6] m");
  check(b.corridor_width >= 1.6 && b.corridor_width <= 6.0, *this, "building.corridor_width",
        "must be in [1.6, 6] m");
  check(b.corridor_length >= 6.0 && b.corridor_length <= 500.0, *this, "building.corridor_length",
        "must be in [6, 500] m");
  check(b.room_depth >= 3.0 && b.room_depth <= 20.0, *this, "building.room_depth",
        "must be in [3, 20] m");
  check(b.room_width >= 2.5 && b.room_width <= 30.0, *this, "building.room_width",
        "must be in [2.5, 30] m");
  check(b.wings == 1 || b.wings == 2, *this, "building.wings", "must be 1 or 2");
  check(b.door_width >= 0.7 && b.door_width < b.room_width - 0.5, *this, "building.door_width",
        "must be in [0.7, room_width - 0.5] m");
  check(b.door_height >= 1.8 && b.door_height <= 2.3, *this, "building.door_height",
        "must be in [1.8, 2.3] m");
  check(b.window_width > 0.2 && b.window_width < b.room_width - 0.6, *this, "building.window_width",
        "must be in (0.2, room_width - 0.6) m");
  check(b.window_sill >= 0.0 && b.window_sill + b.window_height <= 2.3, *this,
        "building.window_height", "window_sill + window_height must be at most 2.3 m");
  check(b.glass_front_fraction >= 0.0 && b.glass_front_fraction <= 1.0, *this,
        "building.glass_front_fraction", "must be in [0, 1]");
  check(b.clutter_density >= 0.0 && b.clutter_density <= 2.0, *this, "building.clutter_density",
        "must be in [0, 2] per metre");
  check(b.pillar_spacing == 0.0 || b.pillar_spacing >= 2.0, *this, "building.pillar_spacing",
        "must be 0 or at least 2 m");
  const StairwellSpec& s = b.stairwell;
  check(s.width >= 2.2 && s.width <= 6.0, *this, "building.stairwell.width",
        "must be in [2.2, 6] m");
  check(s.riser >= 0.12 && s.riser <= 0.21, *this, "building.stairwell.riser",
        "must be in [0.12, 0.21] m");
  check(s.tread >= 0.22 && s.tread <= 0.40, *this, "building.stairwell.tread",
        "must be in [0.22, 0.40] m");
  check(s.floor_landing_depth >= 1.2 && s.floor_landing_depth <= 4.0, *this,
        "building.stairwell.floor_landing_depth", "must be in [1.2, 4] m");
  check(s.half_landing_depth >= 1.0 && s.half_landing_depth <= 4.0, *this,
        "building.stairwell.half_landing_depth", "must be in [1, 4] m");
  check(s.position > 0.0 && s.position < 1.0, *this, "building.stairwell.position",
        "must be in (0, 1)");
  check(
      b.partition_angle >= 60.0 * kDegToRad - 1e-9 && b.partition_angle <= 90.0 * kDegToRad + 1e-9,
      *this, "building.partition_angle_deg", "must be in [60, 90] deg");
  check(b.atrium.rooms >= 0 && b.atrium.rooms <= 20, *this, "building.atrium.rooms",
        "must be in [0, 20]");
  check(b.atrium.position > 0.0 && b.atrium.position < 1.0, *this, "building.atrium.position",
        "must be in (0, 1)");
  check(b.atrium.balustrade_height >= 0.8 && b.atrium.balustrade_height <= 1.5, *this,
        "building.atrium.balustrade_height", "must be in [0.8, 1.5] m");
  check(!b.single_loaded || b.atrium.rooms == 0, *this, "building.atrium.rooms",
        "must be 0 in a single-loaded building (the atrium replaces south rooms)");
  check(b.arms.positions.size() == b.arms.lengths.size(), *this, "building.arms.lengths",
        "must list one length per arm position");
  check(b.arms.rises.empty() || b.arms.rises.size() == b.arms.positions.size(), *this,
        "building.arms.rises", "must be empty or list one rise per arm position");
  for (double r : b.arms.rises)
    check(r >= 0.0 && r <= 1.0, *this, "building.arms.rises", "values must be in [0, 1] m");
  check(b.arms.positions.size() <= 3, *this, "building.arms.positions", "must list at most 3 arms");
  for (double p : b.arms.positions)
    check(p >= 0.0 && p <= 1.0, *this, "building.arms.positions", "values must be in [0, 1]");
  for (double l : b.arms.lengths)
    check(l >= 6.0 && l <= 100.0, *this, "building.arms.lengths", "values must be in [6, 100] m");
  check(robot.rooms_entered >= 0 && robot.rooms_entered <= 4, *this, "robot.rooms_entered",
        "must be in [0, 4]");
  check(robot.rounds >= 1 && robot.rounds <= 20, *this, "robot.rounds", "must be in [1, 20]");
  check(robot.walk_speed > 0.05 && robot.walk_speed <= 2.0, *this, "robot.walk_speed",
        "must be in (0.05, 2] m/s");
  check(robot.stair_speed > 0.05 && robot.stair_speed <= 1.0, *this, "robot.stair_speed",
        "must be in (0.05, 1] m/s");
  check(robot.max_accel >= 0.05 && robot.max_accel <= 3.0, *this, "robot.max_accel",
        "must be in [0.05, 3] m/s^2");
  check(robot.max_lateral_accel >= 0.05 && robot.max_lateral_accel <= 3.0, *this,
        "robot.max_lateral_accel", "must be in [0.05, 3] m/s^2");
  check(robot.max_yaw_rate >= 0.1 && robot.max_yaw_rate <= 3.0, *this, "robot.max_yaw_rate_deg",
        "must be in [6, 170] deg/s");
  check(robot.turn_radius >= 0.1 && robot.turn_radius <= 3.0, *this, "robot.turn_radius",
        "must be in [0.1, 3] m");
  check(robot.body_height >= 0.2 && robot.body_height <= 1.5, *this, "robot.body_height",
        "must be in [0.2, 1.5] m");
  check(robot.lane_offset >= 0.0 && robot.lane_offset < b.corridor_width / 2 - 0.4, *this,
        "robot.lane_offset", "must be in [0, corridor_width/2 - 0.4) m");
  check(robot.still_time >= 0.0 && robot.still_time <= 60.0, *this, "robot.still_time",
        "must be in [0, 60] s");
  check(robot.start_offset >= 0.8, *this, "robot.start_offset", "must be at least 0.8 m");
  check(robot.gait.frequency > 0.0 && robot.gait.frequency <= 10.0, *this,
        "robot.gait.frequency_hz", "must be in (0, 10] Hz");
  check(robot.gait.bounce >= 0.0 && robot.gait.bounce <= 0.1, *this, "robot.gait.bounce",
        "must be in [0, 0.1] m");
  check(std::abs(robot.gait.roll) <= 0.2, *this, "robot.gait.roll_deg", "must be at most 11 deg");
  check(std::abs(robot.gait.pitch) <= 0.2, *this, "robot.gait.pitch_deg", "must be at most 11 deg");
  const HandheldGaitSpec& h = robot.handheld_gait;
  check(h.frequency > 0.0 && h.frequency <= 4.0, *this, "robot.handheld_gait.frequency_hz",
        "must be in (0, 4] Hz");
  check(h.bounce >= 0.0 && h.bounce <= 0.1, *this, "robot.handheld_gait.bounce",
        "must be in [0, 0.1] m");
  check(h.sway >= 0.0 && h.sway <= 0.1, *this, "robot.handheld_gait.sway", "must be in [0, 0.1] m");
  check(std::abs(h.roll) <= 0.2, *this, "robot.handheld_gait.roll_deg", "must be at most 11 deg");
  check(std::abs(h.pitch) <= 0.2, *this, "robot.handheld_gait.pitch_deg", "must be at most 11 deg");
  check(std::abs(h.yaw) <= 0.2, *this, "robot.handheld_gait.yaw_deg", "must be at most 11 deg");
  check(h.slope_pitch >= 0.0 && h.slope_pitch <= 1.0, *this, "robot.handheld_gait.slope_pitch",
        "must be in [0, 1]");
  const LidarSpec& l = sensors.lidar;
  check(l.rotation_rate >= 5.0 && l.rotation_rate <= 20.0, *this, "sensors.lidar.rotation_rate_hz",
        "must be in [5, 20] Hz");
  check(l.range_noise >= 0.0 && l.range_noise <= 0.5, *this, "sensors.lidar.range_noise",
        "must be in [0, 0.5] m");
  check(l.dropout >= 0.0 && l.dropout < 1.0, *this, "sensors.lidar.dropout", "must be in [0, 1)");
  check(l.min_range >= 0.0 && l.min_range < l.max_range, *this, "sensors.lidar.min_range",
        "must be in [0, max_range)");
  check(l.max_range <= 300.0, *this, "sensors.lidar.max_range", "must be at most 300 m");
  check(l.intensity_noise >= 0.0, *this, "sensors.lidar.intensity_noise", "must be >= 0");
  check(isSimulatedLidar(l.model), *this, "sensors.lidar.model",
        std::string("must be one of the simulated LiDARs (") + simulatedLidarNames() + ")");
  check(l.model != LidarModel::kOs1_64 || l.rotation_rate == 10.0 || l.rotation_rate == 20.0, *this,
        "sensors.lidar.rotation_rate_hz", "must be 10 or 20 Hz for an OS1-64");
  const ImuSpec& i = sensors.imu;
  check(i.rate >= 50.0 && i.rate <= 4000.0, *this, "sensors.imu.rate_hz",
        "must be in [50, 4000] Hz");
  check(i.gyro_noise_density >= 0.0 && i.accel_noise_density >= 0.0 && i.gyro_random_walk >= 0.0 &&
            i.accel_random_walk >= 0.0,
        *this, "sensors.imu", "noise densities must be >= 0");
  check(i.gravity > 9.7 && i.gravity < 9.9, *this, "sensors.imu.gravity",
        "must be in (9.7, 9.9) m/s^2");
  if (i.grade) {
    const ImuRateRange rates = imuGradeRates(*i.grade);
    check(i.rate >= rates.min_hz && i.rate <= rates.max_hz, *this, "sensors.imu.rate_hz",
          std::string("must be in [") + numberText(rates.min_hz) + ", " + numberText(rates.max_hz) +
              "] Hz for a " + toString(*i.grade) + " IMU");
  }
  check(i.orientation_sigma.minCoeff() >= 0.0 && i.orientation_sigma.maxCoeff() <= 0.5, *this,
        "sensors.imu.orientation_sigma_deg", "values must be in [0, 28] deg");
  check(sensors.start_time >= 1.0 && sensors.start_time < 4.0e9, *this, "sensors.start_time",
        "must be in [1, 4e9) s");
  check(!sensors.points_topic.empty() && sensors.points_topic[0] == '/', *this,
        "sensors.points_topic", "must start with '/'");
  check(!sensors.imu_topic.empty() && sensors.imu_topic[0] == '/', *this, "sensors.imu_topic",
        "must start with '/'");
}

std::string buildingSpecYaml(const BuildingSpec& spec) {
  BuildingSpec copy = spec;
  YAML::Emitter out;
  out << YAML::Comment("Storey building spec, format version 1 (see docs/simulator.md)");
  out << YAML::BeginMap;
  out << YAML::Key << "format_version" << YAML::Value << 1;
  out << YAML::Key << "name" << YAML::Value << spec.name;
  out << YAML::Key << "seed" << YAML::Value << spec.seed;
  SpecWriter writer{out};
  visitSpec(writer, copy);
  out << YAML::EndMap;
  if (!out.good()) throw Error("building spec: cannot format YAML: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < detail::kEmbeddedPresetCount; ++i)
    names.emplace_back(detail::kEmbeddedPresets[i].name);
  return names;
}

std::string presetText(const std::string& name) {
  for (std::size_t i = 0; i < detail::kEmbeddedPresetCount; ++i) {
    const detail::EmbeddedPreset& p = detail::kEmbeddedPresets[i];
    if (name == p.name) return std::string(p.text, p.size);
  }
  std::string list;
  for (const std::string& n : presetNames()) list += (list.empty() ? "" : ", ") + n;
  throw Error("unknown building preset '" + name + "' (presets: " + list +
              "; or give the path of a building YAML file)");
}

BuildingSpec parseBuildingSpec(const std::string& yaml_text, const std::string& source) {
  const YAML::Node root = parseYaml(yaml_text, source);
  BuildingSpec spec;
  spec.source = source;
  YamlSection top(root, source, "");
  top.read("name", spec.name);
  int seed = static_cast<int>(spec.seed);
  top.read("seed", seed);
  if (seed < 0) top.fail("seed", "must be >= 0");
  spec.seed = static_cast<std::uint64_t>(seed);
  int version = 1;
  top.read("format_version", version);
  if (version != 1) top.fail("format_version", "must be 1");
  SpecReader reader{top};
  visitSpec(reader, spec);
  top.finish();
  spec.validate();
  return spec;
}

BuildingSpec loadBuildingSpec(const std::string& preset_or_path) {
  if (const std::optional<std::uint64_t> seed = randomSeedOf(preset_or_path)) {
    // Through the YAML text, so spec.yaml (that text) gives exactly this spec.
    return parseBuildingSpec(buildingSpecYaml(drawRandomSpec(*seed)), preset_or_path);
  }
  for (const std::string& name : presetNames()) {
    if (name == preset_or_path) return parseBuildingSpec(presetText(name), "preset '" + name + "'");
  }
  std::error_code ec;
  if (!std::filesystem::is_regular_file(preset_or_path, ec)) {
    std::string list;
    for (const std::string& n : presetNames()) list += (list.empty() ? "" : ", ") + n;
    throw Error("'" + preset_or_path + "' is neither a building preset (" + list +
                ") nor a readable YAML file");
  }
  return parseBuildingSpec(readTextFile(preset_or_path), preset_or_path);
}

}  // namespace storey::sim
