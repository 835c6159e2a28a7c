#pragma once
/// What the simulator writes into a log, whatever the container: the ROS1
/// bag (sim/bag_writer.h) or a ROS 2 bag (sim/ros2_bag_writer.h).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "io/ros_messages.h"
#include "sim/organised_scan.h"
#include "types/imu_sample.h"
#include "types/scan.h"

namespace storey::sim {

/// The orientation an IMU reports with a sample.
struct ImuOrientation {
  Eigen::Quaterniond q_world_imu = Eigen::Quaterniond::Identity();
  Eigen::Vector3d variance = Eigen::Vector3d::Zero();  ///< about x, y, z [rad^2]
};

class SimLogWriter {
 public:
  virtual ~SimLogWriter() = default;
  /// Scan with an absolute stamp, in the Velodyne driver's layout; `receipt_ns` is the record time.
  virtual void writeScan(const std::string& topic, const Scan& scan, std::int64_t receipt_ns) = 0;
  /// An organised scan in the Ouster driver's layout (sim/cloud_messages.h).
  virtual void writeOrganisedScan(const std::string& topic, const std::string& frame_id,
                                  const OrganisedScan& scan, std::int64_t stamp_ns,
                                  std::int64_t receipt_ns) = 0;
  /// IMU sample with an absolute stamp, recorded at `record_ns` (its stamp
  /// unless its clock jumped, sim_faults.h). Covariances are
  /// the discrete white-noise variances. Without `orientation` none is
  /// provided (orientation_covariance[0] = -1).
  virtual void writeImu(const std::string& topic, const std::string& frame_id,
                        const ImuSample& sample, std::int64_t record_ns, double gyro_variance,
                        double accel_variance, const ImuOrientation* orientation = nullptr) = 0;
  /// Velodyne packets as a velodyne_msgs/VelodyneScan, recorded at `receipt_ns`.
  virtual void writeVelodyneScan(const std::string& topic, const VelodyneScanMessage& scan,
                                 std::int64_t receipt_ns) = 0;
  virtual void close() = 0;
};

}  // namespace storey::sim
