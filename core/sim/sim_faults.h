#pragma once
/// Faults injected into a simulated log (`storey simulate --fault`), the ones
/// field logs have: a saturated IMU sample, an IMU dropout, a LiDAR blackout.
/// They change what the logs hold, never the ground truth (docs/simulator.md,
/// "Faults").
#include <string>
#include <vector>

namespace storey::sim {

enum class SimFaultKind {
  kImuSpike,  ///< the first IMU sample at or after `time` reads the sensor's full range
  kImuGap,    ///< no IMU samples in [time, time + duration]
  kLidarGap,  ///< no scans stamped in [time, time + duration]
};

struct SimFault {
  SimFaultKind kind = SimFaultKind::kImuSpike;
  double time = 0.0;      ///< since the log's start [s]
  double duration = 0.0;  ///< gaps [s]
};

/// The full-range reading of kImuSpike: 2000 deg/s and 16 g on every axis
/// (signs alternating), a MEMS IMU's usual ranges.
inline constexpr double kSpikeGyro = 34.9;    ///< [rad/s]
inline constexpr double kSpikeAccel = 156.9;  ///< [m/s^2]

/// "imu_spike@T", "imu_gap@T+D" or "lidar_gap@T+D" (seconds since the log's
/// start); storey::Error naming the text otherwise.
SimFault parseSimFault(const std::string& text);
std::string toString(const SimFault& fault);

/// Which samples of time-ordered stamps [s since the start] the faults remove
/// (`drop`) or replace with a full-range reading (`spike`), one flag per stamp.
struct SampleFaults {
  std::vector<char> drop, spike;
};
SampleFaults imuSampleFaults(const std::vector<SimFault>& faults,
                             const std::vector<double>& stamps);
/// Whether a scan stamped `time` [s since the start] falls in a LiDAR gap.
bool inLidarGap(const std::vector<SimFault>& faults, double time);

}  // namespace storey::sim
