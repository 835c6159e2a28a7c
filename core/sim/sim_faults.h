#pragma once
/// Faults injected into a simulated log (`storey simulate --fault`), the ones
/// field logs have: a saturated IMU sample, an IMU dropout, a LiDAR blackout,
/// an IMU clipping at its range, a person in front of the LiDAR, a clock
/// jump in one stream.
/// They change what the logs hold, never the ground truth (docs/simulator.md,
/// "Faults").
#include <cstdint>
#include <string>
#include <vector>

namespace storey::sim {

enum class SimFaultKind {
  kImuSpike,  ///< the first IMU sample at or after `time` reads the sensor's full range
  kImuGap,    ///< no IMU samples in [time, time + duration]
  kLidarGap,  ///< no scans stamped in [time, time + duration]
  /// IMU samples in [time, time + duration] read +range on gyro x and accel z
  kImuSaturation,
  /// scans stamped in [time, time + duration]: the points within 135 deg of
  /// the LiDAR's +x azimuth are at kOcclusionRange along their ray
  kOcclusion,
  kImuClockJump,    ///< IMU samples from `time` on are stamped `step` later
  kLidarClockJump,  ///< scans from `time` on are stamped `step` later
  /// every IMU sample and scan stamped in [time, time + duration] is
  /// recorded twice (a recorder or driver repeating messages)
  kDuplicate,
  /// IMU samples in [time, time + duration]: every other one is recorded
  /// after the sample that follows it (stamps going back by one period)
  kReorder,
  /// [time, time + duration]: every 20th point of each scan and every 40th
  /// IMU sample (its angular rate) are NaN
  kNan,
};

struct SimFault {
  SimFaultKind kind = SimFaultKind::kImuSpike;
  double time = 0.0;      ///< since the log's start [s]
  double duration = 0.0;  ///< gaps, saturation, occlusion [s]
  double step = 0.0;      ///< clock jumps: the stamps' step, signed [s]
};

/// The full-range reading of kImuSpike: 2000 deg/s and 16 g on every axis
/// (signs alternating), a MEMS IMU's usual ranges.
inline constexpr double kSpikeGyro = 34.9;    ///< [rad/s]
inline constexpr double kSpikeAccel = 156.9;  ///< [m/s^2]
/// The body in front of the LiDAR (kOcclusion): its distance [m] (beyond
/// input.min_range, 0.3) and half the sector it hides [rad] (270 deg in all).
inline constexpr float kOcclusionRange = 0.35f;
inline constexpr double kOcclusionHalfSector = 2.356194490192345;

/// "imu_spike@T", "imu_gap@T+D", "lidar_gap@T+D", "imu_saturation@T+D",
/// "occlusion@T+D", "duplicate@T+D", "reorder@T+D", "nan@T+D",
/// "imu_clock_jump@T+S" or "lidar_clock_jump@T+S" (seconds
/// since the log's start; S signed: @T+S or @T-S); storey::Error naming the
/// text otherwise.
SimFault parseSimFault(const std::string& text);
std::string toString(const SimFault& fault);

/// Which samples of time-ordered stamps [s since the start] the faults remove
/// (`drop`), replace with a full-range reading (`spike`), clip at the range
/// on one gyro and one accelerometer axis (`saturate`), record twice
/// (`duplicate`), record after the next sample (`late`) or make NaN (`nan`),
/// one flag per stamp; `shift_ns`: what the clock jumps add to each stamp [ns].
struct SampleFaults {
  std::vector<char> drop, spike, saturate, duplicate, late, nan;
  std::vector<std::int64_t> shift_ns;
};
SampleFaults imuSampleFaults(const std::vector<SimFault>& faults,
                             const std::vector<double>& stamps);
/// Whether a scan stamped `time` [s since the start] falls in a LiDAR gap.
bool inLidarGap(const std::vector<SimFault>& faults, double time);
/// Whether a scan stamped `time` [s since the start] is occluded.
bool inOcclusion(const std::vector<SimFault>& faults, double time);
/// Whether a fault of `kind` covers a scan stamped `time` [s since the start].
bool inFault(const std::vector<SimFault>& faults, SimFaultKind kind, double time);
/// What the LiDAR clock jumps add to the stamp of a scan stamped `time` [ns].
std::int64_t lidarClockShiftNs(const std::vector<SimFault>& faults, double time);
/// Whether `faults` hold one of `kind`.
bool hasFault(const std::vector<SimFault>& faults, SimFaultKind kind);

}  // namespace storey::sim
