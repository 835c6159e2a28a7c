#include "sim/velodyne_scan_stream.h"

#include <cmath>

namespace storey::sim {

VelodyneScanStream::VelodyneScanStream(std::int64_t start_ns, double rotation_hz,
                                       velodyne::Model model, std::string frame_id,
                                       std::string context, int cut_azimuth)
    : builder_(start_ns, rotation_hz, model, std::move(context), cut_azimuth),
      packets_per_message_(
          static_cast<std::size_t>(std::ceil(builder_.packetRate() / rotation_hz))) {
  message_.frame_id = std::move(frame_id);
}

void VelodyneScanStream::add(const VelodyneFiring& sequence,
                             std::vector<VelodyneScanMessage>& done) {
  BuiltPacket built;
  if (builder_.add(sequence, built)) addPacket(built, done);
}

void VelodyneScanStream::finish(std::vector<VelodyneScanMessage>& done) {
  BuiltPacket built;
  if (builder_.finish(built)) addPacket(built, done);
  close(done);
}

void VelodyneScanStream::addPacket(const BuiltPacket& built,
                                   std::vector<VelodyneScanMessage>& done) {
  VelodynePacketMessage& packet = message_.packets.emplace_back();
  packet.stamp_ns = built.complete_ns;
  packet.data = built.payload;
  if (message_.packets.size() >= packets_per_message_) close(done);
}

void VelodyneScanStream::close(std::vector<VelodyneScanMessage>& done) {
  if (message_.packets.empty()) return;
  message_.stamp_ns = message_.packets.back().stamp_ns;
  done.push_back(message_);
  message_.packets.clear();
}

}  // namespace storey::sim
