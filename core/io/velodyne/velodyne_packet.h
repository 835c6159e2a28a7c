#pragma once
/// Decoding of Velodyne data packets (1206-byte UDP payloads) and HDL-32E
/// position packets (512 bytes) into plain values. See docs/formats.md,
/// "Input: Velodyne pcap".
///
/// Data packet: 12 blocks of 100 bytes (flag 0xFFEE, azimuth uint16 in 0.01
/// deg, 32 x (distance uint16 in calibration LSBs, intensity uint8)), then the
/// timestamp (uint32, microseconds past the hour of the first firing of block
/// 0), the return mode byte and the product id byte. VLP-16 blocks hold two
/// firing sequences of 16 lasers; VLP-32C and HDL-32E blocks one sequence of 32. In dual
/// return mode blocks come in pairs (last, strongest-or-second) of the same firing.
///
/// Point frame (the LiDAR frame, as ROS drivers publish it): x towards
/// azimuth 0, y to the left, z up along the spin axis; the head spins
/// clockwise seen from above, so x = r cos(el) cos(az), y = -r cos(el) sin(az),
/// z = r sin(el). (VeloView shows x_veloview = -y, y_veloview = x.)
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "io/velodyne/velodyne_tables.h"

namespace storey::velodyne {

/// How the azimuth of a laser inside a block is obtained.
enum class AzimuthInterpolation {
  kPerLaser,  ///< block azimuth + rotation until the laser fired (the manuals' "precise azimuth")
  kPerSequence,  ///< block azimuth + rotation until the firing sequence started (VeloView 3.x)
  /// nebula's arithmetic (tier4/nebula 606ac41, Vlp16Decoder and Vlp32Decoder), to compare with
  /// clouds it decoded; not what the sensor does for 32-laser models (docs/formats.md):
  /// - block b's azimuth is block b's in single return mode, block b + 1's in dual return mode
  ///   (b >= 1), and the rotation is taken to the block 1 (single) or 2 (dual) further on;
  /// - no rotation for the packet's last block (VLP-32C, HDL-32E: single return; VLP-16: the last
  ///   block in either mode), the previous rotation for the other blocks without a successor;
  /// - inside a block: VLP-16 as kPerLaser; 32-laser models channel c at c x 2.304 / 55.296 of
  ///   the rotation (as if the lasers fired one at a time; the VLP-32C fires them in pairs);
  /// - rounded to 0.01 deg (halves up); distances kept strictly inside (min_range, max_range);
  /// - the azimuth window (DecodeOptions::window) tested on the block azimuth as sent (32-laser
  ///   models) or, for the VLP-16, on this block azimuth (when min < max) and on the rounded one.
  kNebula,
};

/// Returns are kept when their block azimuth (as sent) lies in [min_deg, max_deg], wrapping
/// through 0 when min_deg > max_deg (nebula's cloud_min_angle / cloud_max_angle, the ROS
/// velodyne driver's min_angle / max_angle). The default keeps everything.
struct AzimuthWindow {
  double min_deg = 0.0;
  double max_deg = 360.0;
  bool all() const { return min_deg <= 0.0 && max_deg >= 360.0; }
  /// Whether `azimuth` [0.01 deg] lies in the window.
  bool contains(double azimuth) const;
};

struct DecodeOptions {
  AzimuthInterpolation azimuth = AzimuthInterpolation::kPerLaser;
  double min_range = 0.3;     ///< returns closer are dropped [m]; 0 keeps every non-zero distance
  double max_range = 1000.0;  ///< returns farther are dropped [m]
  /// Dual return: drop the second block's return when it equals the first's (same distance).
  bool drop_identical_second_return = true;
  AzimuthWindow window;  ///< azimuth crop (off by default)
};

/// One laser return.
struct Return {
  float x = 0, y = 0, z = 0;   ///< LiDAR frame [m]
  float distance = 0;          ///< [m]
  float azimuth_deg = 0;       ///< azimuth used for the position [deg], in [0, 360)
  double time_offset_s = 0.0;  ///< firing time after the packet timestamp [s]
  std::uint8_t intensity = 0;  ///< calibrated reflectivity [0, 255]
  std::uint8_t laser = 0;      ///< laser id (channel within its firing sequence)
  std::uint8_t block = 0;      ///< data block in the packet, 0..11
  std::uint8_t sequence = 0;   ///< firing sequence within the block (VLP-16: 0 or 1)
  std::uint16_t ring = 0;      ///< rank by elevation, 0 = lowest
  bool second_return = false;  ///< dual mode: from the pair's second block
};

/// Counts of what a packet held besides the kept returns.
struct PacketCounts {
  std::int64_t no_return = 0;         ///< distance 0
  std::int64_t out_of_range = 0;      ///< outside [min_range, max_range]
  std::int64_t identical_second = 0;  ///< dual mode: second return equal to the first
  std::int64_t outside_window = 0;    ///< outside DecodeOptions::window
};

struct DataPacket {
  std::uint32_t timestamp_us = 0;  ///< microseconds past the hour (sensor clock)
  std::uint8_t return_mode = 0;    ///< ReturnMode value as sent
  std::uint8_t product = 0;        ///< product id byte as sent
  std::array<std::uint16_t, kBlocksPerPacket> block_azimuth{};  ///< [0.01 deg]
  std::vector<Return> returns;  ///< kept returns in packet order (block, sequence, laser)
  PacketCounts counts;
  bool dual() const { return return_mode == static_cast<std::uint8_t>(ReturnMode::kDual); }
};

/// Why a payload is not a usable data packet.
enum class PacketProblem {
  kNone,
  kWrongSize,     ///< not 1206 bytes
  kBadBlockFlag,  ///< a block does not start with 0xFFEE
  kBadAzimuth,    ///< a block azimuth > 36000 (36000 itself is sent for 0)
  kUnknownReturnMode,
};
const char* toString(PacketProblem problem);

/// Reads the packet's trailer only (timestamp, return mode, product).
bool peekDataPacket(const std::uint8_t* data, std::size_t size, std::uint32_t& timestamp_us,
                    std::uint8_t& return_mode, std::uint8_t& product);

class PacketDecoder {
 public:
  PacketDecoder(Calibration calibration, DecodeOptions options);

  /// Decodes one payload into `packet` (its returns vector reused).
  PacketProblem decode(const std::uint8_t* data, std::size_t size, DataPacket& packet) const;

  /// Firing time of (block, sequence, laser) after the packet timestamp [s].
  double firingOffset(int block, int sequence, int laser, bool dual) const;

  const Calibration& calibration() const { return calibration_; }
  Model model() const { return calibration_.model; }

 private:
  Calibration calibration_;
  DecodeOptions options_;
  std::vector<double> cos_el_, sin_el_;
};

/// The built-in IMU of an HDL-32E as sent in its position packets: three
/// single-axis gyros, three temperatures and three 2-axis accelerometers, each
/// a 12-bit two's complement value in the low bits of a little-endian uint16
/// (bytes 14..37 in the order gyro, temp, accel X, accel Y for boards 1, 2, 3).
/// Scales (HDL-32E manual, Appendix B): gyro 0.09766 deg/s per LSB, temperature
/// 0.1453 C per LSB + 25 C, acceleration 0.001221 g per LSB.
struct PositionPacket {
  std::uint32_t timestamp_us =
      0;  ///< microseconds past the hour (same clock as data packets), byte 198
  std::array<double, 3> gyro_dps{};  ///< boards 1..3 [deg/s]
  std::array<double, 3> temp_c{};    ///< boards 1..3 [C]
  std::array<double, 6> accel_g{};   ///< X1, Y1, X2, Y2, X3, Y3 [g]
  bool has_nmea = false;             ///< a "$GP" sentence at byte 206
};

/// Decodes a 512-byte position packet; false when the size is wrong.
bool decodePositionPacket(const std::uint8_t* data, std::size_t size, PositionPacket& packet);

}  // namespace storey::velodyne
