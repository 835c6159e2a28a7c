#pragma once
/// The simulator's input: a building spec (YAML, resources/buildings/*.yaml)
/// describing the building, the robot's walk and the sensors. Units: metres,
/// seconds, radians inside; the YAML gives angles in degrees. Every field has
/// a default; docs/simulator.md lists the YAML keys.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "types/pose.h"
#include "types/sensor.h"

namespace storey::sim {

/// How the stairs link the storeys (docs/simulator.md, "Stairs").
enum class StairKind {
  kSwitchback,  ///< an enclosed stairwell: two flights and a half landing per storey
  kStraight,    ///< open straight flights along the corridor, one per storey, side by side
  kLShaped,     ///< two flights at a right angle round an open well, a quarter landing between
};
const char* toString(StairKind kind);
/// "switchback", "straight" or "l_shaped"; storey::Error listing them otherwise.
StairKind stairKindFromString(const std::string& name);

/// The stairs linking all storeys, north of the corridor.
struct StairwellSpec {
  StairKind kind = StairKind::kSwitchback;
  double width = 2.8;   ///< across both flights (kStraight: both lanes) [m]
  double riser = 0.17;  ///< nominal riser; the real one divides the storey height evenly [m]
  double tread = 0.28;  ///< [m]
  /// Landing at each floor, between corridor and flights (kStraight: at
  /// both ends of the flights, along the corridor) [m].
  double floor_landing_depth = 1.6;
  double half_landing_depth = 1.4;  ///< [m] (kSwitchback)
  double position = 0.8;  ///< centre along the corridor, as a fraction of its length [0, 1]
};

/// An atrium: a void through every storey above the ground floor in place of
/// some of the south rooms, open to the corridor behind a balustrade, so the
/// floors of other storeys are seen across it. The ground floor under it is
/// an open hall.
struct AtriumSpec {
  int rooms = 0;                   ///< south rooms it replaces; 0 = no atrium
  double position = 0.5;           ///< its centre along the corridor, as a fraction [0, 1]
  bool glass_balustrade = true;    ///< glass (LiDAR sees through) or a solid parapet
  double balustrade_height = 1.1;  ///< [m]
};

/// Wings at right angles to the corridor, on its south side (the stairwell's
/// is north): one at an end makes an L, one in the middle a T, one at each end
/// a U. An arm is a corridor as wide as the main one with rooms as deep on
/// both sides; it starts at the main corridor's south wall, replacing the
/// south rooms it covers, and ends in a glazed end wall.
struct ArmsSpec {
  /// Where each arm's axis meets the corridor, as a fraction of its length
  /// (0 and 1: flush with the west and east ends) [0, 1].
  std::vector<double> positions;
  std::vector<double> lengths;  ///< from the main corridor's south wall to the arm's end [m]
  /// How much higher each arm's floors are than the main building's, reached
  /// by a ramp of 1:12 at the start of its corridor (split levels); empty =
  /// all level [0, 1] [m].
  std::vector<double> rises;
};

struct BuildingLayoutSpec {
  std::vector<double> storey_heights{3.2};  ///< floor-to-floor height of each storey, bottom up [m]
  double slab_thickness = 0.25;             ///< floor/ceiling slab [m]
  double wall_thickness = 0.15;             ///< [m]
  double corridor_length = 20.0;            ///< along x [m]
  double corridor_width = 2.2;              ///< [m]
  double room_depth = 5.0;                  ///< rooms on both sides of the corridor [m]
  double room_width = 4.0;                  ///< nominal; rooms divide each side evenly [m]
  int wings = 1;  ///< 1: stairwell near the east end; 2: corridor wings on both sides of it
  /// Rooms on the north side only: the corridor's south wall is an outer wall
  /// with windows (a single-loaded corridor); no atrium then.
  bool single_loaded = false;
  double door_width = 0.9;     ///< [m]
  double door_height = 2.1;    ///< [m]
  double window_width = 1.6;   ///< glass windows in the outer walls [m]
  double window_sill = 0.9;    ///< [m]
  double window_height = 1.4;  ///< [m]
  double glass_front_fraction =
      0.2;                        ///< fraction of rooms with a glass wall to the corridor [0, 1]
  double clutter_density = 0.35;  ///< objects per metre of corridor wall, per side [1/m]
  double pillar_spacing = 6.0;    ///< pillars along the corridor walls; 0 = none [m]
  /// Angle between the room partitions and the corridor walls [rad] (YAML:
  /// degrees, 60-90): below 90 deg the partitions lean towards +x, so rooms
  /// are parallelograms and walls meet at that angle.
  double partition_angle = M_PI / 2;
  StairwellSpec stairwell;
  AtriumSpec atrium;
  ArmsSpec arms;
};

/// How the sensors are carried: the kind of walk, and the defaults of RobotSpec.
enum class RobotMotion {
  kLegged,    ///< a quadruped trotting, sensors on its body (GaitSpec)
  kHandheld,  ///< a person walking with the sensors in hand (HandheldGaitSpec)
};
const char* toString(RobotMotion motion);
/// "legged" or "handheld"; storey::Error listing them otherwise.
RobotMotion robotMotionFromString(const std::string& name);

struct GaitSpec {
  double frequency = 2.5;  ///< trot frequency [Hz]
  double bounce = 0.015;   ///< vertical amplitude [m]
  double roll = 0.0175;    ///< roll amplitude [rad] (YAML: degrees)
  double pitch = 0.014;    ///< pitch amplitude [rad] (YAML: degrees)
};

/// A hand-held sensor on a walking person (defaults: docs/simulator.md,
/// "Handheld walking"). Step-frequency terms repeat every step, stride terms
/// every two steps (left, right).
struct HandheldGaitSpec {
  double frequency = 1.9;    ///< step frequency [Hz]
  double bounce = 0.02;      ///< vertical amplitude, step frequency (peak to peak 2x) [m]
  double sway = 0.015;       ///< lateral amplitude, stride frequency [m]
  double slope_pitch = 0.5;  ///< share of the stair slope the device pitches with [0, 1]
  /// Roll amplitude, stride frequency [rad] (YAML: degrees; 2).
  double roll = 0.03490658503988659;
  /// Pitch amplitude, step frequency [rad] (YAML: degrees; 1.5).
  double pitch = 0.02617993877991494;
  /// Yaw amplitude, stride frequency [rad] (YAML: degrees; 1.5).
  double yaw = 0.02617993877991494;
};

struct RobotSpec {
  /// Which gait rides on the walk; robotForMotion() gives each one's defaults.
  RobotMotion motion = RobotMotion::kLegged;
  double walk_speed = 0.8;          ///< cruise speed on floors [m/s]
  double stair_speed = 0.3;         ///< speed along the stair slope [m/s]
  double max_accel = 0.4;           ///< along the path [m/s^2]
  double max_lateral_accel = 0.35;  ///< in turns [m/s^2]
  double max_yaw_rate = 0.7;        ///< [rad/s] (YAML: degrees/s)
  double turn_radius = 0.5;         ///< corner fillet radius, reduced where space is short [m]
  double body_height = 0.5;         ///< body centre above the floor / stair line [m]
  double lane_offset = 0.35;        ///< walking lanes at +-offset from the corridor axis [m]
  double still_time = 2.0;          ///< standing still at start and end [s]
  double start_offset = 2.5;        ///< start position from the west end of the corridor [m]
  /// Rooms of the main corridor the walk goes into on each storey it walks
  /// (through the door, round the middle of the room and out) [0, 4].
  int rooms_entered = 0;
  /// Times the route is walked, one round after the other without stopping
  /// (it ends where and heading the way it starts), for long logs [1, 20].
  int rounds = 1;
  GaitSpec gait;  ///< motion kLegged
  /// Motion kHandheld.
  HandheldGaitSpec handheld_gait;
};

/// The robot defaults of a motion: kLegged the RobotSpec defaults; kHandheld
/// a person's walk (1.0 m/s, 0.5 m/s on stairs, turns up to 90 deg/s, the
/// sensors 1.2 m above the floor).
RobotSpec robotForMotion(RobotMotion motion);

struct LidarSpec {
  /// The simulated sensor (sim/lidar_model.h; not kGeneric).
  LidarModel model = LidarModel::kVlp16;
  double rotation_rate = 10.0;   ///< revolutions per second [Hz]
  double range_noise = 0.015;    ///< sigma along the beam [m]
  double dropout = 0.01;         ///< probability a return is lost [0, 1]
  double min_range = 0.4;        ///< [m]
  double max_range = 100.0;      ///< [m]
  double intensity_noise = 2.0;  ///< sigma [sensor units]
};

/// Named classes of IMU, with noise figures from a datasheet (imuGrade()).
enum class ImuGrade {
  kTactical,  ///< industrial/tactical MEMS, Xsens MTi-300 class, 200-400 Hz
  kConsumer,  ///< consumer MEMS, Bosch BMI088 class, 100-200 Hz
};
const char* toString(ImuGrade grade);
/// "tactical" or "consumer"; storey::Error listing them otherwise.
ImuGrade imuGradeFromString(const std::string& name);

struct ImuSpec {
  /// The class the values come from; empty = "custom" (the values as given).
  std::optional<ImuGrade> grade;
  double rate = 400.0;                               ///< [Hz]
  double gyro_noise_density = 1.75e-4;               ///< [rad/s/sqrt(Hz)]
  double accel_noise_density = 5.9e-4;               ///< [m/s^2/sqrt(Hz)]
  double gyro_random_walk = 1.0e-5;                  ///< [rad/s^2/sqrt(Hz)]
  double accel_random_walk = 1.0e-4;                 ///< [m/s^3/sqrt(Hz)]
  double gravity = 9.81;                             ///< [m/s^2]
  Eigen::Vector3d gyro_bias{0.002, -0.0015, 0.001};  ///< initial bias [rad/s]
  Eigen::Vector3d accel_bias{0.03, -0.02, 0.04};     ///< initial bias [m/s^2]
  /// sensor_msgs/Imu carries the orientation (true R_world_imu) with
  /// orientation_sigma as its covariance; false: orientation_covariance[0] = -1.
  bool orientation = false;
  /// Roll, pitch, yaw standard deviation stated with the orientation [rad]
  /// (YAML: degrees; 0.3, 0.3, 1).
  Eigen::Vector3d orientation_sigma{0.005235987755982988, 0.005235987755982988,
                                    0.017453292519943295};
};

/// The ImuSpec of a grade at `rate_hz` (datasheet figures: docs/simulator.md,
/// "IMU grades"); storey::Error when the rate is outside the grade's range.
ImuSpec imuGrade(ImuGrade grade, double rate_hz);
/// The output rates of a grade's class [Hz]; the top one is its nominal rate.
struct ImuRateRange {
  double min_hz = 0.0, max_hz = 0.0;
};
ImuRateRange imuGradeRates(ImuGrade grade);

struct SensorsSpec {
  Pose T_body_lidar{Eigen::Quaterniond::Identity(), Eigen::Vector3d(0.25, 0.0, 0.12)};
  Pose T_body_imu;  ///< IMU at the body centre by default
  LidarSpec lidar;
  ImuSpec imu;
  double start_time = 1.7e9;  ///< stamp of the first sample [s since epoch]
  std::string points_topic = "/velodyne_points";
  std::string imu_topic = "/imu/data";
  std::string lidar_frame_id = "velodyne";
  std::string imu_frame_id = "imu";
};

struct BuildingSpec {
  std::string name = "custom";
  std::string source;      ///< file or preset it came from (for messages)
  std::uint64_t seed = 1;  ///< clutter layout and sensor noise
  BuildingLayoutSpec building;
  RobotSpec robot;
  SensorsSpec sensors;

  /// Checks ranges; throws storey::Error naming the source and key.
  void validate() const;
};

/// Names of the presets compiled into the binary (resources/buildings/*.yaml).
std::vector<std::string> presetNames();
/// The YAML text of a preset; throws storey::Error listing the presets when unknown.
std::string presetText(const std::string& name);

/// Parses a spec from YAML text; `source` names it in errors. Unknown keys,
/// wrong types and out-of-range values are storey::Error naming source, key, line.
BuildingSpec parseBuildingSpec(const std::string& yaml_text, const std::string& source);
/// The spec as YAML (every key, the format parseBuildingSpec reads; numbers
/// with 17 digits, mounts as quaternions): parseBuildingSpec(buildingSpecYaml(s))
/// writes the same text again.
std::string buildingSpecYaml(const BuildingSpec& spec);
/// A preset name (see presetNames()) or a path to a YAML file.
BuildingSpec loadBuildingSpec(const std::string& preset_or_path);

}  // namespace storey::sim
