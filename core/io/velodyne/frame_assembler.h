#pragma once
/// Cuts the stream of decoded Velodyne packets into frames (one revolution
/// each) where the block azimuth wraps: a new frame starts at the first block
/// whose azimuth is smaller than the previous block's (VeloView's rule, so the
/// first and last frames of a capture are usually partial). A gap in time
/// longer than `max_gap_s` also starts a new frame.
#include <cstdint>
#include <vector>

#include "io/velodyne/velodyne_packet.h"
#include "types/scan.h"

namespace storey::velodyne {

class FrameAssembler {
 public:
  explicit FrameAssembler(const PacketDecoder& decoder, double max_gap_s = 0.5)
      : decoder_(decoder), max_gap_ns_(static_cast<std::int64_t>(max_gap_s * 1e9)) {}

  /// Adds a packet whose timestamp is `packet_ns` (absolute); appends the
  /// frames it completes to `done` (stamp = firing time of the frame's first
  /// block, point times relative to it).
  void add(const DataPacket& packet, std::int64_t packet_ns, std::vector<Scan>& done);
  /// The frame in progress, if it has points, goes to `done`.
  void flush(std::vector<Scan>& done);

  std::int64_t framesStarted() const { return frames_started_; }
  std::int64_t gapCuts() const { return gap_cuts_; }

 private:
  void close(std::vector<Scan>& done);

  const PacketDecoder& decoder_;
  std::int64_t max_gap_ns_;
  Scan current_;
  bool open_ = false;
  int last_azimuth_ = -1;
  std::int64_t last_block_ns_ = 0;
  std::int64_t frames_started_ = 0;
  std::int64_t gap_cuts_ = 0;
};

}  // namespace storey::velodyne
