#pragma once
/// How logs are read (the `input:` section of the configuration).
#include <string>

namespace storey {

struct InputConfig {
  std::string points_topic;  ///< PointCloud2 topic; empty = auto-detect
  std::string imu_topic;     ///< Imu topic; empty = auto-detect
  double min_range = 0.3;    ///< points closer than this are dropped [m] (robot body, sensor head)
  double max_range = 120.0;  ///< points farther than this are dropped [m]
  // Velodyne pcap, PCD folder and IMU CSV inputs (docs/formats.md).
  std::string imu_csv;  ///< IMU CSV file; empty = none (PCD folder: imu.csv inside it)
  double imu_csv_time_offset =
      0.0;  ///< added to the CSV's stamps to put them on the LiDAR clock [s]
  std::string velodyne_model = "auto";  ///< pcap: auto (from packets), VLP-16, VLP-32C, HDL-32E
  std::string velodyne_calibration;  ///< pcap: VeloView calibration XML; empty = the manual's table
  /// Velodyne packets (pcap, VelodyneScan): a frame starts where the head
  /// passes this azimuth [deg, 0..360); 0 = where the azimuth wraps (VeloView).
  double velodyne_cut_angle_deg = 0.0;
  std::string pcap_clock =
      "sensor";               ///< pcap: "sensor" (packet timestamps) or "capture" (record times)
  int pcap_data_port = 2368;  ///< pcap: UDP port of data packets; 0 = any port
  int pcap_position_port = 8308;  ///< pcap: UDP port of position (IMU) packets; 0 = any port
  /// An IMU sample whose angular rate differs from its two neighbours' mean
  /// by more than this while they agree (within half of it) is a spike (a
  /// saturated or garbled reading), replaced by their interpolation; 0 = off [rad/s].
  double imu_spike_gyro = 10.0;
  /// The same for the specific force [m/s^2] (60: about 6 g); 0 = off.
  double imu_spike_accel = 60.0;
  /// At least three consecutive IMU samples holding the same value on one
  /// gyro axis, at least this far from zero, are a saturated run (the sensor
  /// clipped at its range): removed, the IMU factor across it gets the
  /// uncertainty of unknown motion; 0 = off [rad/s] (4: below the smallest
  /// common range, 250 deg/s).
  double imu_saturation_gyro = 4.0;
  /// The same for the specific force [m/s^2] (19: below 2 g); 0 = off.
  double imu_saturation_accel = 19.0;
  /// A scan with fewer points beyond 0.5 m than this fraction of the median
  /// of the last 50 clear scans is occluded (a person in front of the
  /// sensor): its points within 0.5 m are removed, and with less than 10 %
  /// of the usual left it is skipped; 0 = off [-].
  double lidar_occlusion_fraction = 0.4;
  /// Scans read, decoded and checked ahead on a thread of their own while
  /// the current one is registered (io/read_ahead_log_reader.h); 0 = the log
  /// is read on the run's own thread. The results are the same either way.
  int read_ahead_scans = 4;

  /// Checks value ranges; throws storey::Error naming the key (under `input.`) at fault.
  void validate() const;
};

}  // namespace storey
