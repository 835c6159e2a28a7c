#pragma once
/// Turns velodyne_msgs/VelodyneScan messages (ROS 1 or ROS 2 bags) into
/// Scans with the Velodyne decoder of the pcap path: the model from the first
/// packet's factory bytes, packets placed on the sensor clock (their
/// microseconds past the hour, in the hour of the packet's stamp), frames cut
/// at `input.velodyne_cut_angle_deg` (by default where the azimuth wraps), not
/// at message boundaries, so the scans are those of a capture of the same
/// packets. See docs/formats.md.
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "io/input_config.h"
#include "io/ros_messages.h"
#include "io/velodyne/frame_assembler.h"
#include "io/velodyne/packet_model.h"
#include "io/velodyne/velodyne_packet.h"
#include "types/scan.h"

namespace storey {

/// Keys of LogReadStats::dropped for VelodyneScan packets (counts of packets).
inline constexpr const char* kDropScanPacketBad = "velodyne_packet_damaged";
inline constexpr const char* kDropScanPacketBackwards = "velodyne_packet_not_newer";

struct VelodyneScanOptions {
  std::optional<velodyne::Model> model;  ///< forced; empty = from the packets
  std::string calibration_xml;           ///< VeloView XML; empty = the manual's table
  double min_range = 0.3;                ///< [m]
  double max_range = 120.0;              ///< [m]
  double cut_angle_deg = 0.0;            ///< frames start at this azimuth [deg]; 0 = the wrap
  bool capture_clock = false;            ///< packet stamps instead of the sensor clock
};
VelodyneScanOptions velodyneScanOptions(const InputConfig& input);

class VelodyneScanDecoder {
 public:
  /// `source` names the file and topic in errors and warnings.
  VelodyneScanDecoder(std::string source, VelodyneScanOptions options);
  ~VelodyneScanDecoder();

  /// Decodes the packets of one message; completed frames go to `done`,
  /// what was dropped to `dropped`. Throws storey::Error (prefixed by
  /// `source`) for a model Storey cannot decode.
  void add(const VelodyneScanMessage& message, std::vector<Scan>& done,
           std::map<std::string, std::int64_t>& dropped);
  /// The frame in progress goes to `done`.
  void flush(std::vector<Scan>& done);

  bool started() const { return decoder_ != nullptr; }
  velodyne::Model model() const;
  const velodyne::ModelDetection& detection() const { return detection_; }
  std::uint8_t product() const { return product_; }
  std::uint8_t returnMode() const { return return_mode_; }
  std::int64_t packets() const { return packets_; }

 private:
  void start(const VelodyneScanMessage& message);

  std::string source_;
  VelodyneScanOptions options_;
  velodyne::ModelDetection detection_;
  std::uint8_t product_ = 0;
  std::uint8_t return_mode_ = 0;
  std::unique_ptr<velodyne::PacketDecoder> decoder_;
  std::unique_ptr<velodyne::FrameAssembler> frames_;
  velodyne::HourClock clock_;
  velodyne::DataPacket decoded_;
  bool have_last_ = false;
  std::int64_t last_ns_ = 0;
  std::int64_t packets_ = 0;
};

}  // namespace storey
