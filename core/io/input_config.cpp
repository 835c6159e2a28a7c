#include "io/input_config.h"

#include "common/error.h"

namespace storey {

void InputConfig::validate() const {
  requireKey(min_range >= 0.0, "input.min_range", "must be >= 0");
  requireKey(max_range > min_range, "input.max_range", "must be larger than 'input.min_range'");
  requireKey(velodyne_model == "auto" || velodyne_model == "VLP-16" ||
                 velodyne_model == "VLP-32C" || velodyne_model == "HDL-32E",
             "input.velodyne_model", "must be auto, VLP-16, VLP-32C or HDL-32E");
  requireKey(velodyne_cut_angle_deg >= 0.0 && velodyne_cut_angle_deg < 360.0,
             "input.velodyne_cut_angle_deg", "must be in [0, 360)");
  requireKey(pcap_clock == "sensor" || pcap_clock == "capture", "input.pcap_clock",
             "must be sensor or capture");
  requireKey(pcap_data_port >= 0 && pcap_data_port <= 65535, "input.pcap_data_port",
             "must be a UDP port (0 = any)");
  requireKey(pcap_position_port >= 0 && pcap_position_port <= 65535, "input.pcap_position_port",
             "must be a UDP port (0 = any)");
  requireKey(imu_spike_gyro >= 0.0, "input.imu_spike_gyro", "must be >= 0 (0 = off)");
  requireKey(imu_spike_accel >= 0.0, "input.imu_spike_accel", "must be >= 0 (0 = off)");
  requireKey(imu_saturation_gyro >= 0.0, "input.imu_saturation_gyro", "must be >= 0 (0 = off)");
  requireKey(imu_saturation_accel >= 0.0, "input.imu_saturation_accel", "must be >= 0 (0 = off)");
  requireKey(lidar_occlusion_fraction >= 0.0 && lidar_occlusion_fraction < 1.0,
             "input.lidar_occlusion_fraction", "must be in [0, 1) (0 = off)");
  requireKey(read_ahead_scans >= 0 && read_ahead_scans <= 64, "input.read_ahead_scans",
             "must be in [0, 64] (0 = read on the run's thread)");
}

}  // namespace storey
