#pragma once
/// What the factory bytes and timestamps of Velodyne data packets tell,
/// shared by the pcap reader and the VelodyneScan decoder: the model, the
/// time one packet spans, and the packets' microseconds-past-the-hour placed
/// on an absolute clock.
#include <cstdint>
#include <string>

#include "io/velodyne/velodyne_tables.h"

namespace storey::velodyne {

/// Time spanned by one data packet of `model` [s] (halved in dual return mode).
double packetPeriod(Model model, bool dual);

struct ModelDetection {
  Model model = Model::kVlp16;
  bool from_product_id = false;  ///< else from the packet period
};

/// The model from the product id byte (0x22 VLP-16, 0x24 VLP-16 Hi-Res with
/// a warning, 0x28 VLP-32C); for 0x21 (HDL-32E, also early VLP-16 firmware) or
/// 0x00 from `packet_period_s` (the median time between packets; 0 = unknown,
/// then HDL-32E). A forced model wins, with a warning when it disagrees.
/// Throws storey::Error naming `source` for VLS-128 / HDL-64E ids.
ModelDetection detectModel(std::uint8_t product, std::uint8_t return_mode, double packet_period_s,
                           const Model* forced, const std::string& source);

/// "0x28"
std::string hexByte(std::uint8_t value);

/// Places packet timestamps (microseconds past the hour) on an absolute
/// clock: the hour comes from the first packet's reference time (record or
/// receipt time; the hour nearest to it) and advances when the timestamps wrap.
class HourClock {
 public:
  /// Absolute time [ns] of `toh_us`; `advance` lets it move the newest time
  /// (data packets), else it is only placed (position packets).
  std::int64_t place(std::uint32_t toh_us, std::int64_t reference_ns, bool advance);

 private:
  bool have_hour_ = false;
  std::int64_t hour_base_ns_ = 0;
  std::int64_t newest_ns_ = 0;
};

}  // namespace storey::velodyne
