#pragma once
/// Deskew: every point of a scan is moved to the scan's reference time (its
/// header stamp) using the IMU-propagated motion at the point's own time.
///
/// A point x measured at time t = stamp + time_offset + tau (IMU clock) is
///   x_ref = T_lidar_imu * T_world_imu(t_ref)^-1 * T_world_imu(t) * T_imu_lidar * x
/// with t_ref = stamp + time_offset, so only the motion inside the scan matters.
#include "imu/imu_pose_table.h"
#include "types/scan.h"
#include "types/sensor.h"

namespace storey {

/// The deskewed copy of `scan` (point times kept, so they still say when each
/// point was measured). `table` must start at or before the reference time;
/// times past its end are extrapolated at constant velocity.
Scan deskewScan(const Scan& scan, const ImuPoseTable& table, const SensorConfig& sensor);

}  // namespace storey
