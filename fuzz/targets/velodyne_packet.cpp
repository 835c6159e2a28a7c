// Velodyne packet decoding for every model: byte 0 picks the model (VLP-16,
// VLP-32C, HDL-32E), the azimuth interpolation and the dual-return filter;
// the rest is one UDP payload (data packet, position packet) and, cut into
// 1206-byte packets, a velodyne_msgs/VelodyneScan for the frame assembly.
#include <algorithm>
#include <map>
#include <vector>

#include "fuzz_common.h"
#include "io/ros_messages.h"
#include "io/velodyne/velodyne_packet.h"
#include "io/velodyne/velodyne_scan_decoder.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace vel = storey::velodyne;
  storey::fuzz::quietLogs();
  if (size < 1) return 0;
  const auto model = static_cast<vel::Model>(data[0] % 3);
  const std::uint8_t* payload = data + 1;
  const std::size_t payload_size = size - 1;
  storey::fuzz::expectOnlyStoreyErrors([&] {
    vel::DecodeOptions options;
    options.azimuth = (data[0] & 4) ? vel::AzimuthInterpolation::kPerSequence
                                    : vel::AzimuthInterpolation::kPerLaser;
    options.drop_identical_second_return = (data[0] & 8) == 0;
    options.min_range = (data[0] & 16) ? 0.0 : 0.3;
    const vel::PacketDecoder decoder(vel::defaultCalibration(model), options);
    vel::DataPacket packet;
    decoder.decode(payload, payload_size, packet);
    std::uint32_t timestamp_us = 0;
    std::uint8_t return_mode = 0, product = 0;
    vel::peekDataPacket(payload, payload_size, timestamp_us, return_mode, product);
    vel::PositionPacket position;
    vel::decodePositionPacket(payload, payload_size, position);

    storey::VelodyneScanMessage scan;
    scan.stamp_ns = 1700000000000000000;
    for (std::size_t at = 0; at < payload_size; at += storey::kVelodynePacketBytes) {
      storey::VelodynePacketMessage p;
      p.stamp_ns = scan.stamp_ns + static_cast<std::int64_t>(at) * 1000;
      std::copy_n(payload + at, std::min(storey::kVelodynePacketBytes, payload_size - at),
                  p.data.begin());
      scan.packets.push_back(p);
    }
    storey::VelodyneScanOptions scan_options;
    if (data[0] & 32) scan_options.model = model;
    scan_options.capture_clock = (data[0] & 64) != 0;
    storey::VelodyneScanDecoder scans("fuzz.bag /velodyne_packets", scan_options);
    std::vector<storey::Scan> done;
    std::map<std::string, std::int64_t> dropped;
    scans.add(scan, done, dropped);
    scans.flush(done);
  });
  return 0;
}
