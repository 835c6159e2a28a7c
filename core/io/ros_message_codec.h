#pragma once
/// sensor_msgs/PointCloud2, sensor_msgs/Imu and velodyne_msgs/VelodyneScan
/// read from (and written to) their serialized bytes in ROS 1 serialization
/// or CDR (io/ros_wire.h). Each decoder takes a byte buffer, so it can be
/// fed any input (fuzzing); a damaged message throws storey::Error naming
/// the field and byte (the caller adds file, topic and message index).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "io/ros_messages.h"
#include "io/ros_wire.h"

namespace storey {

void decodePointCloud2(const std::uint8_t* data, std::size_t size, WireFormat format,
                       PointCloudMessage& out);
ImuMessage decodeImu(const std::uint8_t* data, std::size_t size, WireFormat format);
void decodeVelodyneScan(const std::uint8_t* data, std::size_t size, WireFormat format,
                        VelodyneScanMessage& out);
/// The header stamp of a message whose type starts with a std_msgs/Header.
std::int64_t decodeHeaderStamp(const std::uint8_t* data, std::size_t size, WireFormat format);

std::vector<std::uint8_t> encodePointCloud2(const PointCloudMessage& cloud, WireFormat format,
                                            std::uint32_t seq = 0);
/// Covariances: diagonal gyro/accel variances; orientation none
/// (orientation_covariance[0] = -1) unless `orientation_xyzw` is given.
std::vector<std::uint8_t> encodeImu(const ImuSample& sample, const std::string& frame_id,
                                    double gyro_variance, double accel_variance,
                                    const double* orientation_xyzw,
                                    const double* orientation_variance, WireFormat format,
                                    std::uint32_t seq = 0);
std::vector<std::uint8_t> encodeVelodyneScan(const VelodyneScanMessage& scan, WireFormat format,
                                             std::uint32_t seq = 0);

/// Message definitions (ROS 1 .msg text, also the ROS 2 "ros2msg" schema
/// text with the nested types appended) of the three types, as recorders store them.
const char* rosMessageDefinition(const std::string& canonical_type, WireFormat format);

}  // namespace storey
