#pragma once
/// The LiDAR models the simulator fires: each one's beam table, firing timing,
/// range step and the layout its ROS driver publishes. The Velodyne tables and
/// timing are the decoder's (io/velodyne/velodyne_tables.h, from the manuals),
/// so a simulated capture decodes to what was fired.
///
/// A channel is one beam of a firing sequence: a Velodyne laser id (firing
/// order), an Ouster row (0 = top beam). A firing sequence (Velodyne) or a
/// column (Ouster) fires every channel once; the head turns clockwise seen
/// from above.
#include <cstdint>
#include <optional>
#include <vector>

#include "io/velodyne/velodyne_tables.h"
#include "types/sensor.h"

namespace storey::sim {

/// How the model's ROS driver lays out a scan's sensor_msgs/PointCloud2.
enum class CloudLayout {
  kVelodyne,  ///< velodyne_pointcloud: returns only, in firing order (docs/simulator.md)
  kOuster,    ///< ouster-ros: organised, rows = beams from the top, no-returns kept as zeros
};

struct LidarBeams {
  LidarModel model = LidarModel::kVlp16;
  CloudLayout layout = CloudLayout::kVelodyne;
  std::vector<double> elevation;       ///< by channel [rad], positive up
  std::vector<double> azimuth_offset;  ///< by channel, added to the head's azimuth, clockwise [rad]
  std::vector<std::int64_t> firing_ns;  ///< by channel, after the sequence's first firing [ns]
  std::vector<std::uint16_t> ring;      ///< by channel: rank by elevation, 0 = lowest
  /// Velodyne: between the starts of two firing sequences [ns]; 0 when the
  /// sequences are columns of a revolution (Ouster).
  std::int64_t sequence_period_ns = 0;
  int columns = 0;               ///< Ouster: columns per revolution (0 for Velodyne)
  double distance_step = 0.002;  ///< range resolution of the sensor's packets [m]

  int channels() const { return static_cast<int>(elevation.size()); }
};

/// Whether the simulator has a model of `model` (not LidarModel::kGeneric).
bool isSimulatedLidar(LidarModel model);
/// The simulated models, as a list for messages ("VLP-16, VLP-32C, ...").
const char* simulatedLidarNames();

/// The capture decoder's model of a Velodyne LiDAR (its tables, its
/// packets); empty for the others.
std::optional<velodyne::Model> velodyneModel(LidarModel model);

/// The beams of a simulated model; storey::Error for kGeneric.
///  VLP-16:  16 lasers -15..+15 deg, one every 2.304 us, sequences of 55.296 us, 2 mm.
///  VLP-32C: 32 lasers -25..+15 deg (uneven), azimuth offsets +-1.4/+-4.2 deg,
///           pairs every 2.304 us, sequences of 55.296 us, 4 mm.
///  HDL-32E: 32 lasers -30.67..+10.67 deg, one every 1.152 us, sequences of 46.08 us, 2 mm.
///  OS1-64:  an Ouster OS1-64-like sensor: 64 beams evenly from +22.5 (row 0)
///           to -22.5 deg, all fired at once, 1024 columns per revolution, 1 mm.
LidarBeams lidarBeams(LidarModel model);

}  // namespace storey::sim
