#pragma once
/// Cuts the stream of decoded Velodyne packets into frames (one revolution
/// each) at a cut azimuth, as the ROS velodyne driver's `cut_angle` does: a
/// new frame starts at the first block whose azimuth has passed the cut
/// (startsFrame). With the default cut, 0 deg, that is where the block
/// azimuth wraps (a block's azimuth smaller than the previous block's,
/// VeloView's rule), so the first and last frames of a capture are usually
/// partial. A gap in time longer than `max_gap_s` also starts a new frame.
#include <cstdint>
#include <vector>

#include "io/velodyne/velodyne_packet.h"
#include "types/scan.h"

namespace storey::velodyne {

/// A gap in time longer than this starts a new frame [s].
inline constexpr double kMaxFrameGapS = 0.5;

/// The cut azimuth of `input.velodyne_cut_angle_deg` [deg, 0..360) in the
/// packets' unit, 0..35999 [0.01 deg].
int cutAzimuth(double cut_angle_deg);

/// Whether a block whose azimuth is `azimuth` starts a new frame after a block
/// at `previous` (both as sent, 0.01 deg) when frames are cut at `cut`
/// (0..35999): the head turned through the cut between the two blocks,
/// `previous < cut <= azimuth`; a decrease of the azimuth is a turn through
/// 0 deg (36000), so then the cut is passed when `cut > previous` or
/// `cut <= azimuth`. Cut 0: exactly where the azimuth decreases.
inline bool startsFrame(int previous, int azimuth, int cut) {
  if (azimuth < previous) return cut > previous || cut <= azimuth;
  return previous < cut && cut <= azimuth;
}

class FrameAssembler {
 public:
  /// `cut_azimuth`: where frames start [0.01 deg, 0..35999] (cutAzimuth).
  explicit FrameAssembler(const PacketDecoder& decoder, double max_gap_s = kMaxFrameGapS,
                          int cut_azimuth = 0)
      : decoder_(decoder),
        max_gap_ns_(static_cast<std::int64_t>(max_gap_s * 1e9)),
        cut_azimuth_(cut_azimuth) {}

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
  int cut_azimuth_;
  Scan current_;
  bool open_ = false;
  int last_azimuth_ = -1;
  std::int64_t last_block_ns_ = 0;
  std::int64_t frames_started_ = 0;
  std::int64_t gap_cuts_ = 0;
};

}  // namespace storey::velodyne
