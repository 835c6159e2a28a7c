#pragma once
/// LogReader for Velodyne captures (pcap / pcapng of the sensor's UDP
/// packets, as VeloView or tcpdump record them): VLP-16 (single or dual
/// return) and HDL-32E data packets cut into one scan per revolution, the
/// HDL-32E's position packets as IMU samples, or an IMU CSV. See
/// docs/formats.md, "Input: Velodyne pcap".
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "io/input_config.h"
#include "io/log_reader.h"
#include "io/velodyne/velodyne_packet.h"
#include "types/sensor.h"

namespace storey {

/// Keys of LogReadStats::dropped (counts of packets unless named otherwise).
inline constexpr const char* kDropNotVelodyne = "udp_not_velodyne";  ///< other ports / sizes
inline constexpr const char* kDropPacketTruncated = "velodyne_packet_truncated";
inline constexpr const char* kDropPacketLate =
    "velodyne_packet_out_of_order";  ///< too late to reorder
inline constexpr const char* kDropPacketDuplicate = "velodyne_packet_duplicate";
inline constexpr const char* kDropPacketOtherModel = "velodyne_packet_other_model";
inline constexpr const char* kDropPositionTruncated = "position_packet_truncated";
inline constexpr const char* kDropPositionNoImu = "position_packet_without_imu";
inline constexpr const char* kDropPointsNoReturn = "velodyne_point_no_return";  ///< points
inline constexpr const char* kDropPointsRange = "velodyne_point_out_of_range";  ///< points
inline constexpr const char* kDropPointsDualIdentical =
    "velodyne_point_dual_identical";  ///< points
inline constexpr const char* kDropImuBeforeLog =
    "imu_csv_before_log";  ///< samples long before the first scan
inline constexpr const char* kDropScanBeyondImu =
    "scan_beyond_imu_end";  ///< last scan outlasts the IMU
inline constexpr const char* kReorderedPackets =
    "velodyne_packet_reordered";  ///< repaired, not dropped

struct VelodynePcapOptions {
  std::optional<velodyne::Model> model;  ///< forced model; empty = detected from the packets
  std::string calibration_xml;           ///< VeloView XML; empty = the manual's table
  velodyne::AzimuthInterpolation azimuth = velodyne::AzimuthInterpolation::kPerLaser;
  double min_range = 0.3;              ///< [m]
  double max_range = 120.0;            ///< [m]
  double cut_angle_deg = 0.0;          ///< frames start at this azimuth [deg]; 0 = where it wraps
  bool capture_clock = false;          ///< stamp with record times instead of packet timestamps
  std::uint16_t data_port = 2368;      ///< 0 = any port (recognised by size and block flags)
  std::uint16_t position_port = 8308;  ///< 0 = any port
  std::string imu_csv;                 ///< IMU CSV; empty = the position packets' IMU if any
  std::int64_t imu_csv_offset_ns = 0;  ///< added to the CSV stamps
  std::int64_t lidar_to_imu_offset_ns = 0;  ///< sensor.time_offset_lidar_to_imu (ordering only)
  bool require_imu = true;                  ///< throw at open when no IMU source exists
  /// Hold each scan until an IMU sample at or after its last point has been
  /// read, and drop the scans at the end of the capture that the IMU does not
  /// cover (counted as scan_beyond_imu_end). Off: every revolution is delivered.
  bool drop_scans_beyond_imu = true;
  std::size_t reorder_packets = 64;  ///< data packets held to repair reordering
};

/// Builds the options from a configuration (input.* keys, sensor.time_offset_lidar_to_imu).
VelodynePcapOptions velodynePcapOptions(const InputConfig& input, const SensorConfig& sensor);

/// What the first packets of a capture tell (read at open).
struct VelodyneProbe {
  velodyne::Model model = velodyne::Model::kVlp16;
  bool model_from_product_id = false;  ///< else from the packet period
  std::uint8_t product = 0;            ///< product id byte of the first data packet
  std::uint8_t return_mode = 0;        ///< return mode byte of the first data packet
  double packet_period_s = 0.0;        ///< median time between data packets [s]
  std::int64_t data_packets = 0;       ///< among the probed records
  std::int64_t position_packets = 0;   ///< with IMU values
};

class VelodynePcapReader final : public LogReader {
 public:
  /// Opens the capture, detects the model and the IMU source. Throws
  /// storey::Error naming the file when it cannot be read, holds no Velodyne
  /// data packet, or (require_imu) has no IMU source.
  VelodynePcapReader(const std::string& path, const VelodynePcapOptions& options);
  ~VelodynePcapReader() override;

  bool next(LogMessage& message) override;
  const LogReadStats& stats() const override;
  std::string describe() const override;
  double progress() const override;

  const VelodyneProbe& probe() const;
  /// Spin rate over the last (up to 2000) data packets [Hz]; 0 before two packets.
  double rotationHz() const;
  /// "position packets", "IMU CSV <path>" or "none".
  std::string imuSource() const;
  /// Data packets decoded so far.
  std::int64_t dataPackets() const;
  /// UDP datagrams by destination port read so far.
  const std::map<std::uint16_t, std::int64_t>& datagramsByPort() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Opens a capture as a LogReader with the configuration's options.
std::unique_ptr<LogReader> openVelodynePcapLog(const std::string& path, const InputConfig& input,
                                               const SensorConfig& sensor);

}  // namespace storey
