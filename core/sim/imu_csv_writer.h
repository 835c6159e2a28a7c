#pragma once
/// Writes IMU samples as the IMU CSV that Storey reads for Velodyne captures
/// and PCD folders (docs/formats.md, "Input: IMU CSV"):
///   # comment lines
///   time,gyro_x,gyro_y,gyro_z,accel_x,accel_y,accel_z
///   1700000000.002500000,0.0021,-0.0014,0.0009,0.031,-0.018,9.851
/// time in seconds with all nine decimals (the stamp to the nanosecond),
/// angular rate [rad/s] and specific force [m/s^2] in the IMU frame, each in
/// the shortest text that reads back to the same double.
#include <cstdint>
#include <string>
#include <vector>

#include "types/imu_sample.h"

namespace storey::sim {

/// Writes `samples` (stamps + `stamp_offset_ns`) to `path` after the
/// `comment` lines (each prefixed with "# "). Throws storey::Error naming the file.
void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples,
                 std::int64_t stamp_offset_ns, const std::vector<std::string>& comment = {});

/// One CSV line (no newline) of a sample with an absolute stamp.
std::string imuCsvLine(const ImuSample& sample);

}  // namespace storey::sim
