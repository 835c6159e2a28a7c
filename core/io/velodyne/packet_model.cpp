#include "io/velodyne/packet_model.h"

#include <cmath>
#include <cstdio>

#include "common/error.h"
#include "common/log.h"

namespace storey::velodyne {
namespace {

constexpr std::int64_t kHourNs = 3'600'000'000'000LL;
constexpr std::int64_t kHalfHourNs = kHourNs / 2;

}  // namespace

std::string hexByte(std::uint8_t value) {
  char text[8];
  std::snprintf(text, sizeof(text), "0x%02X", value);
  return text;
}

double packetPeriod(Model model, bool dual) {
  const int sequences_per_block = model == Model::kVlp16 ? 2 : 1;
  const double single = kBlocksPerPacket * sequences_per_block * sequencePeriod(model);
  return dual ? single / 2 : single;
}

ModelDetection detectModel(std::uint8_t product, std::uint8_t return_mode, double packet_period_s,
                           const Model* forced, const std::string& source) {
  ModelDetection out;
  const bool dual = return_mode == static_cast<std::uint8_t>(ReturnMode::kDual);
  switch (product) {
    case kProductVlp16:
    case 0x24:  // VLP-16 Hi-Res (Puck Hi-Res): same packets, other elevations
      out.model = Model::kVlp16;
      out.from_product_id = true;
      if (product == 0x24) {
        logWarning(source +
                   ": product id 0x24 (VLP-16 Hi-Res): decoded with the VLP-16 layout; "
                   "give its laser table with input.velodyne_calibration");
      }
      break;
    case kProductVlp32c:
      out.model = Model::kVlp32c;
      out.from_product_id = true;
      break;
    case 0x31:
    case 0xA1:
    case 0x11:
    case 0x12:
      throw Error(source + ": Velodyne product id " + hexByte(product) +
                  " (VLS-128 or HDL-64E) is not supported; Storey decodes VLP-16, VLP-32C and "
                  "HDL-32E");
    default: {
      // 0x21 (HDL-32E, also sent by early VLP-16 firmware) or 0x00: tell the
      // models apart by the time one packet spans.
      const double p = packet_period_s;
      const double vlp = p > 0.0 ? std::abs(std::log(p / packetPeriod(Model::kVlp16, dual))) : 0.0;
      const double hdl = p > 0.0 ? std::abs(std::log(p / packetPeriod(Model::kHdl32e, dual))) : 0.0;
      out.model = (p > 0.0 && vlp < hdl) ? Model::kVlp16 : Model::kHdl32e;
    }
  }
  if (forced != nullptr && *forced != out.model) {
    logWarning(source + ": the packets look like " + toString(out.model) +
               " but input.velodyne_model is " + toString(*forced) + "; decoding as " +
               toString(*forced));
    out.model = *forced;
  }
  return out;
}

std::int64_t HourClock::place(std::uint32_t toh_us, std::int64_t reference_ns, bool advance) {
  const std::int64_t toh_ns = std::int64_t{toh_us} * 1000;
  if (!have_hour_) {
    const double hours = std::round(static_cast<double>(reference_ns - toh_ns) / kHourNs);
    hour_base_ns_ = static_cast<std::int64_t>(hours) * kHourNs;
    newest_ns_ = hour_base_ns_ + toh_ns;
    have_hour_ = true;
  }
  std::int64_t t = hour_base_ns_ + toh_ns;
  while (t < newest_ns_ - kHalfHourNs) t += kHourNs;
  while (t > newest_ns_ + kHalfHourNs) t -= kHourNs;
  if (advance && t > newest_ns_) {
    newest_ns_ = t;
    hour_base_ns_ = t - toh_ns;
  }
  return t;
}

}  // namespace storey::velodyne
