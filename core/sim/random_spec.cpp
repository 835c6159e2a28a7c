#include "sim/random_spec.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "sim/building.h"
#include "sim/random.h"

namespace storey::sim {
namespace {

constexpr double kDeg = M_PI / 180.0;

/// Rounded to a millimetre (or 0.01 deg), so spec.yaml reads like a hand-written spec.
double mm(double v) {
  return std::round(v * 1000.0) / 1000.0;
}

/// `motion`'s robot defaults, keeping where the walk goes: the lanes, the
/// start, the still time, the rooms and the rounds of `robot`.
RobotSpec withMotion(const RobotSpec& robot, RobotMotion motion) {
  RobotSpec moved = robotForMotion(motion);
  moved.lane_offset = robot.lane_offset;
  moved.start_offset = robot.start_offset;
  moved.still_time = robot.still_time;
  moved.rooms_entered = robot.rooms_entered;
  moved.rounds = robot.rounds;
  return moved;
}

int uniformInt(Random& rng, int lo, int hi) {
  return lo + static_cast<int>(std::floor(rng.uniform() * (hi - lo + 1)));
}

Pose mount(const Eigen::Vector3d& translation, double roll, double pitch, double yaw) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  return Pose(q, translation);
}

BuildingSpec draw(std::uint64_t seed, std::uint64_t attempt) {
  Random rng(seed, 0x72616e64ULL + attempt);  // "rand"
  BuildingSpec spec;
  spec.name = "random-" + std::to_string(seed);
  spec.seed = seed;
  BuildingLayoutSpec& b = spec.building;

  // Storeys: 2-7, unequal; a tall ground storey half of the time.
  const int storeys = uniformInt(rng, 2, 7);
  b.storey_heights.clear();
  for (int k = 0; k < storeys; ++k) {
    const bool tall_ground = k == 0 && rng.uniform() < 0.5;
    b.storey_heights.push_back(mm(tall_ground ? rng.uniform(3.6, 4.8) : rng.uniform(2.7, 4.0)));
  }
  b.slab_thickness = mm(rng.uniform(0.2, 0.4));
  b.wall_thickness = mm(rng.uniform(0.1, 0.25));

  // Plan: one corridor (one wing or two), shorter when there are many storeys
  // so that a walk stays within about 25 minutes.
  b.wings = rng.uniform() < 0.5 ? 1 : 2;
  const double max_length = std::clamp(200.0 / (storeys * b.wings), 18.0, 40.0);
  b.corridor_length = mm(rng.uniform(16.0, max_length));
  b.corridor_width = mm(rng.uniform(1.8, 3.0));
  b.room_depth = mm(rng.uniform(3.5, 7.0));
  b.room_width = mm(rng.uniform(3.0, 6.0));
  b.door_width = mm(rng.uniform(0.8, 1.0));
  b.door_height = mm(rng.uniform(2.0, 2.2));
  b.window_width = mm(rng.uniform(0.8, std::min(2.4, b.room_width - 0.8)));
  b.window_sill = mm(rng.uniform(0.6, 1.0));
  b.window_height = mm(rng.uniform(1.0, 2.3 - b.window_sill));
  b.glass_front_fraction = mm(rng.uniform(0.0, 0.5));
  b.clutter_density = mm(rng.uniform(0.1, 0.6));
  b.pillar_spacing = rng.uniform() < 0.3 ? 0.0 : mm(rng.uniform(4.0, 8.0));

  // Stairs: slope 25-38 deg with riser 0.15-0.20 m and tread 0.25-0.32 m.
  StairwellSpec& s = b.stairwell;
  const double slope = rng.uniform(25.0, 38.0) * kDeg;
  s.tread = mm(rng.uniform(0.25, 0.32));
  s.riser = mm(std::clamp(s.tread * std::tan(slope), 0.15, 0.20));
  s.width = mm(rng.uniform(2.4, 3.6));
  s.floor_landing_depth = mm(rng.uniform(1.3, 2.5));
  s.half_landing_depth = mm(rng.uniform(1.1, 2.0));
  s.position = mm(b.wings == 2 ? rng.uniform(0.35, 0.65) : rng.uniform(0.3, 0.85));

  // The walk.
  RobotSpec& r = spec.robot;
  r.walk_speed = mm(rng.uniform(0.6, 1.1));
  r.stair_speed = mm(rng.uniform(0.25, 0.45));
  r.max_yaw_rate = mm(rng.uniform(40.0, 90.0)) * kDeg;
  r.turn_radius = mm(rng.uniform(0.3, 0.8));
  r.body_height = mm(rng.uniform(0.4, 0.7));
  // Lanes keep clear of the clutter along the corridor walls (up to 0.3 m deep).
  r.lane_offset =
      mm(rng.uniform(0.0, std::max(0.0, b.corridor_width / 2 - b.wall_thickness / 2 - 0.6)));
  r.start_offset = mm(rng.uniform(2.0, 4.0));
  r.still_time = 2.0;
  r.gait.frequency = mm(rng.uniform(2.0, 3.0));
  r.gait.bounce = mm(rng.uniform(0.008, 0.025));
  r.gait.roll = mm(rng.uniform(0.5, 2.0)) * kDeg;
  r.gait.pitch = mm(rng.uniform(0.5, 2.0)) * kDeg;

  // Sensors: the LiDAR on the head, upright or pitched 0-25 deg, any yaw;
  // the IMU anywhere within 0.3 m of the body centre, in any orientation.
  SensorsSpec& sensors = spec.sensors;
  const double lidar_pitch = rng.uniform() < 0.5 ? 0.0 : mm(rng.uniform(0.0, 25.0)) * kDeg;
  const double lidar_yaw = mm(rng.uniform(-180.0, 180.0)) * kDeg;
  sensors.T_body_lidar =
      mount(Eigen::Vector3d(mm(rng.uniform(0.1, 0.3)), mm(rng.uniform(-0.05, 0.05)),
                            mm(rng.uniform(0.05, 0.25))),
            0.0, lidar_pitch, lidar_yaw);
  Eigen::Vector3d lever(rng.normal(), rng.normal(), rng.normal());
  lever = lever.normalized() * rng.uniform(0.0, 0.3);
  const double imu_roll = mm(rng.uniform(-180.0, 180.0)) * kDeg;
  const double imu_pitch = mm(rng.uniform(-90.0, 90.0)) * kDeg;
  const double imu_yaw = mm(rng.uniform(-180.0, 180.0)) * kDeg;
  sensors.T_body_imu = mount(Eigen::Vector3d(mm(lever.x()), mm(lever.y()), mm(lever.z())), imu_roll,
                             imu_pitch, imu_yaw);
  sensors.imu.rate = rng.uniform() < 0.5 ? 200.0 : 400.0;
  // Initial biases: a tactical-grade spread (the IMU grades: docs/simulator.md).
  for (int i = 0; i < 3; ++i) {
    sensors.imu.gyro_bias[i] = mm(rng.uniform(-3.0, 3.0)) * 1e-3;
    sensors.imu.accel_bias[i] = mm(rng.uniform(-0.05, 0.05));
  }

  // Partitions at 60-85 deg to the corridor in a third of the buildings.
  if (rng.uniform() < 0.35) b.partition_angle = mm(rng.uniform(60.0, 85.0)) * kDeg;

  // An atrium in a third of the buildings (the generator refuses one that
  // leaves no south room; that draw is redrawn).
  if (rng.uniform() < 0.35) {
    b.atrium.rooms = uniformInt(rng, 1, 3);
    b.atrium.position = mm(rng.uniform(0.2, 0.8));
    b.atrium.glass_balustrade = rng.uniform() < 0.5;
    b.atrium.balustrade_height = mm(rng.uniform(1.0, 1.2));
  }

  // The rig and the walk (drawn after the building, so its draw is unchanged).
  static constexpr LidarModel kModels[] = {LidarModel::kVlp16, LidarModel::kVlp32c,
                                           LidarModel::kHdl32e, LidarModel::kOs1_64};
  sensors.lidar.model = kModels[uniformInt(rng, 0, 3)];
  const ImuGrade grade = rng.uniform() < 0.5 ? ImuGrade::kTactical : ImuGrade::kConsumer;
  const ImuRateRange rates = imuGradeRates(grade);
  const double rate = rng.uniform() < 0.5 ? rates.max_hz : rates.max_hz / 2;
  sensors.imu = imuGrade(grade, std::max(rate, rates.min_hz));
  const double gyro_bias = grade == ImuGrade::kTactical ? 3e-3 : 1.5e-2;  // [rad/s]
  const double accel_bias = grade == ImuGrade::kTactical ? 0.05 : 0.2;    // [m/s^2]
  for (int i = 0; i < 3; ++i) {
    sensors.imu.gyro_bias[i] = mm(rng.uniform(-gyro_bias, gyro_bias) * 1000.0) / 1000.0;
    sensors.imu.accel_bias[i] = mm(rng.uniform(-accel_bias, accel_bias));
  }
  sensors.imu.orientation = rng.uniform() < 0.5;
  if (rng.uniform() < 0.4) {
    // A person walking with the sensors in hand: a person's speeds and gait.
    RobotSpec handheld = withMotion(r, RobotMotion::kHandheld);
    handheld.walk_speed = mm(rng.uniform(0.8, 1.3));
    handheld.stair_speed = mm(rng.uniform(0.4, 0.6));
    handheld.max_yaw_rate = mm(rng.uniform(60.0, 90.0)) * kDeg;
    HandheldGaitSpec& g = handheld.handheld_gait;
    g.frequency = mm(rng.uniform(1.7, 2.1));
    g.bounce = mm(rng.uniform(0.015, 0.025));  // amplitude: 3-5 cm peak to peak
    g.roll = mm(rng.uniform(1.0, 3.0)) * kDeg;
    g.pitch = mm(rng.uniform(1.0, 2.5)) * kDeg;
    g.yaw = mm(rng.uniform(1.0, 2.5)) * kDeg;
    r = handheld;
  }

  // The footprint and the walk's rooms (drawn last, so the draws above are
  // unchanged): a single-loaded corridor in a fifth of the buildings without
  // an atrium; arms making an L, T or U in two fifths; rooms entered on every
  // storey in half; a wide (monumental) stairwell in a sixth; open straight
  // stairs in a third, L-shaped ones in a third of the others.
  if (b.atrium.rooms == 0 && rng.uniform() < 0.2) b.single_loaded = true;
  if (rng.uniform() < 0.4) {
    const double shape = rng.uniform();
    if (shape < 0.4) {
      b.arms.positions = {rng.uniform() < 0.5 ? 0.0 : 1.0};  // L
    } else if (shape < 0.7) {
      b.arms.positions = {mm(rng.uniform(0.3, 0.7))};  // T
    } else {
      b.arms.positions = {0.0, 1.0};  // U
    }
    // The corridor is long enough for its arms and a room or two besides.
    const double arm_width = b.corridor_width + 2 * b.room_depth;
    b.corridor_length = mm(std::max(b.corridor_length, b.arms.positions.size() * arm_width + 5.0));
    // Each arm reaches 5-14 m beyond the main building's rooms, less in tall
    // buildings so that a walk stays within about 25 minutes.
    const double reach =
        std::clamp(120.0 / (storeys * static_cast<double>(b.arms.positions.size())), 5.0, 14.0);
    for (std::size_t i = 0; i < b.arms.positions.size(); ++i)
      b.arms.lengths.push_back(mm(b.room_depth + rng.uniform(5.0, reach)));
  }
  if (rng.uniform() < 0.5) r.rooms_entered = uniformInt(rng, 1, 2);
  if (rng.uniform() < 1.0 / 6.0) s.width = mm(rng.uniform(4.0, 5.5));
  // Open straight flights along the corridor in a third of the buildings.
  if (rng.uniform() < 1.0 / 3.0) {
    s.kind = StairKind::kStraight;
    // The flights run along the corridor: make it long enough for the
    // longest one, its landings and the start west of them.
    double run = 0.0;
    for (std::size_t k = 0; k + 1 < b.storey_heights.size(); ++k)
      run = std::max(run, (std::max(4.0, std::round(b.storey_heights[k] / s.riser)) - 1) * s.tread);
    const double half = run / 2 + s.floor_landing_depth;
    b.corridor_length = mm(std::max(b.corridor_length, 2 * half + 9.0));
    s.position = mm(std::max(s.position, (half + 6.0) / b.corridor_length));
  } else if (rng.uniform() < 0.35) {
    // L-shaped stairs round an open well in a third of the others: room for
    // the walkway west of them.
    s.kind = StairKind::kLShaped;
    const double half = s.width + 2.0;  // at least half the stairs' width
    b.corridor_length = mm(std::max(b.corridor_length, 2 * half + 9.0));
    s.position = mm(std::max(s.position, (half + 6.0) / b.corridor_length));
  }
  // Split levels: in a third of the buildings with arms, the arms' floors
  // 0.3-0.6 m above the main building's, up a 1:12 ramp (the arm long enough
  // for it and a turn).
  if (!b.arms.positions.empty() && rng.uniform() < 0.35) {
    for (std::size_t i = 0; i < b.arms.positions.size(); ++i) {
      b.arms.rises.push_back(mm(rng.uniform(0.3, 0.6)));
      b.arms.lengths[i] = mm(std::max(b.arms.lengths[i], b.arms.rises[i] * 12.0 + 5.0));
    }
  }
  return spec;
}

}  // namespace

BuildingSpec drawRandomSpec(std::uint64_t seed) {
  std::string last_error;
  for (std::uint64_t attempt = 0; attempt < 64; ++attempt) {
    BuildingSpec spec = draw(seed, attempt);
    spec.source = "random:" + std::to_string(seed);
    try {
      spec.validate();
      generateBuilding(spec);  // the generator's own checks (room for the stairs, the start)
      return spec;
    } catch (const Error& e) {
      last_error = e.what();
    }
  }
  throw Error("random:" + std::to_string(seed) + ": no valid building in 64 draws (" + last_error +
              ")");
}

void applyRigOverrides(BuildingSpec& spec, const RigOverrides& o) {
  try {
    if (!o.lidar.empty()) spec.sensors.lidar.model = lidarModelFromString(o.lidar);
  } catch (const Error& e) {
    throw Error(std::string("--lidar: ") + e.what());
  }
  if (!o.imu.empty()) {
    const std::size_t at = o.imu.find('@');
    try {
      const ImuGrade grade = imuGradeFromString(o.imu.substr(0, at));
      double rate = imuGradeRates(grade).max_hz;
      if (at != std::string::npos) {
        std::size_t used = 0;
        rate = std::stod(o.imu.substr(at + 1), &used);
        if (used != o.imu.size() - at - 1) throw Error("'" + o.imu + "': the rate is not a number");
      }
      const bool orientation = spec.sensors.imu.orientation;
      spec.sensors.imu = imuGrade(grade, rate);
      spec.sensors.imu.orientation = orientation;
    } catch (const std::invalid_argument&) {
      throw Error("--imu: '" + o.imu + "': expected GRADE or GRADE@RATE_HZ");
    } catch (const Error& e) {
      throw Error(std::string("--imu: ") + e.what());
    }
  }
  if (!o.motion.empty()) {
    RobotMotion motion;
    try {
      motion = robotMotionFromString(o.motion);
    } catch (const Error& e) {
      throw Error(std::string("--motion: ") + e.what());
    }
    if (motion != spec.robot.motion) {
      spec.robot = withMotion(spec.robot, motion);
    }
  }
}

std::optional<std::uint64_t> randomSeedOf(const std::string& name) {
  const std::string prefix = "random:";
  if (name.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  const std::string digits = name.substr(prefix.size());
  if (digits.empty() || digits.size() > 18 ||
      !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
    throw Error("'" + name + "': a random building is random:SEED with SEED a whole number");
  return std::stoull(digits);
}

}  // namespace storey::sim
