#pragma once
/// The Velodyne sensor and its ROS driver as a simulated log records them:
/// firing sequences -> data packets (VelodynePacketBuilder) ->
/// velodyne_msgs/VelodyneScan messages of one revolution's packets each,
/// stamped (and recorded) at their last packet, as the ROS drivers publish
/// them. A packet bag writes the messages; a point-cloud bag writes what the
/// driver decodes from them (velodyne_pointcloud), which Storey's own decoder
/// (VelodyneScanDecoder) stands in for, so both bags of one walk carry the
/// same points to the bit.
#include <cstdint>
#include <string>
#include <vector>

#include "io/ros_messages.h"
#include "sim/velodyne_packet_builder.h"

namespace storey::sim {

class VelodyneScanStream {
 public:
  /// `start_ns`: the absolute time of VelodyneFiring::t_ns = 0; `cut_azimuth`
  /// [0.01 deg]: where a reader cuts the packets into frames (frameStarts).
  VelodyneScanStream(std::int64_t start_ns, double rotation_hz, velodyne::Model model,
                     std::string frame_id, std::string context, int cut_azimuth);

  /// Adds the next firing sequence; appends the messages it completes to `done`.
  void add(const VelodyneFiring& sequence, std::vector<VelodyneScanMessage>& done);
  /// Completes the last packet and appends the last message, if any.
  void finish(std::vector<VelodyneScanMessage>& done);

  /// VelodynePacketBuilder::frameStarts.
  const std::vector<std::int64_t>& frameStarts() const { return builder_.frameStarts(); }

 private:
  void addPacket(const BuiltPacket& built, std::vector<VelodyneScanMessage>& done);
  void close(std::vector<VelodyneScanMessage>& done);

  VelodynePacketBuilder builder_;
  std::size_t packets_per_message_;
  VelodyneScanMessage message_;
};

}  // namespace storey::sim
