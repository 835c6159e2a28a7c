#include "io/velodyne/frame_assembler.h"

#include <cmath>

namespace storey::velodyne {

int cutAzimuth(double cut_angle_deg) {
  const long a = std::lround(cut_angle_deg * 100.0) % 36000;
  return static_cast<int>(a < 0 ? a + 36000 : a);
}

void FrameAssembler::close(std::vector<Scan>& done) {
  if (open_ && !current_.points.empty()) done.push_back(std::move(current_));
  current_ = Scan{};
  open_ = false;
}

void FrameAssembler::flush(std::vector<Scan>& done) {
  close(done);
}

void FrameAssembler::add(const DataPacket& packet, std::int64_t packet_ns,
                         std::vector<Scan>& done) {
  const bool dual = packet.dual();
  std::size_t next_return = 0;
  for (int b = 0; b < kBlocksPerPacket; ++b) {
    const int azimuth = packet.block_azimuth[b];
    const std::int64_t block_ns =
        packet_ns + static_cast<std::int64_t>(decoder_.firingOffset(b, 0, 0, dual) * 1e9 + 0.5);
    const bool cut = last_azimuth_ >= 0 && startsFrame(last_azimuth_, azimuth, cut_azimuth_);
    const bool gap = open_ && block_ns - last_block_ns_ > max_gap_ns_;
    if (gap) ++gap_cuts_;
    if (cut || gap || !open_) {
      if (open_ || cut || gap) close(done);
      open_ = true;
      ++frames_started_;
      current_.stamp_ns = block_ns;
      current_.frame_id = "velodyne";
    }
    last_azimuth_ = azimuth;
    last_block_ns_ = block_ns;
    for (; next_return < packet.returns.size() && packet.returns[next_return].block == b;
         ++next_return) {
      const Return& r = packet.returns[next_return];
      ScanPoint p;
      p.p = Eigen::Vector3f(r.x, r.y, r.z);
      p.intensity = r.intensity;
      p.ring = r.ring;
      const std::int64_t t_ns = packet_ns + static_cast<std::int64_t>(r.time_offset_s * 1e9 + 0.5);
      p.time = static_cast<float>(static_cast<double>(t_ns - current_.stamp_ns) * 1e-9);
      current_.points.push_back(p);
    }
  }
}

}  // namespace storey::velodyne
