#include "io/velodyne/velodyne_scan_decoder.h"

#include <algorithm>

#include "common/error.h"
#include "io/velodyne/frame_assembler.h"
#include "io/velodyne/velodyne_pcap_reader.h"

namespace storey {

VelodyneScanOptions velodyneScanOptions(const InputConfig& input) {
  VelodyneScanOptions o;
  if (input.velodyne_model == "VLP-16") o.model = velodyne::Model::kVlp16;
  if (input.velodyne_model == "VLP-32C") o.model = velodyne::Model::kVlp32c;
  if (input.velodyne_model == "HDL-32E") o.model = velodyne::Model::kHdl32e;
  o.calibration_xml = input.velodyne_calibration;
  o.min_range = input.min_range;
  o.max_range = input.max_range;
  o.cut_angle_deg = input.velodyne_cut_angle_deg;
  o.capture_clock = input.pcap_clock == "capture";
  return o;
}

VelodyneScanDecoder::VelodyneScanDecoder(std::string source, VelodyneScanOptions options)
    : source_(std::move(source)), options_(std::move(options)) {}

VelodyneScanDecoder::~VelodyneScanDecoder() = default;

velodyne::Model VelodyneScanDecoder::model() const {
  return detection_.model;
}

void VelodyneScanDecoder::start(const VelodyneScanMessage& message) {
  const auto& first = message.packets.front().data;
  std::uint32_t toh;
  velodyne::peekDataPacket(first.data(), first.size(), toh, return_mode_, product_);
  // The median step between the packets' own timestamps (for 0x21 / 0x00 ids).
  std::vector<double> steps;
  for (std::size_t i = 1; i < message.packets.size(); ++i) {
    std::uint32_t a, b;
    std::uint8_t mode, product;
    velodyne::peekDataPacket(message.packets[i - 1].data.data(), kVelodynePacketBytes, a, mode,
                             product);
    velodyne::peekDataPacket(message.packets[i].data.data(), kVelodynePacketBytes, b, mode,
                             product);
    if (b > a && b - a < 100'000) steps.push_back((b - a) * 1e-6);
  }
  double period = 0.0;
  if (!steps.empty()) {
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    period = steps[steps.size() / 2];
  }
  detection_ = velodyne::detectModel(product_, return_mode_, period,
                                     options_.model ? &*options_.model : nullptr, source_);
  velodyne::DecodeOptions decode;
  decode.min_range = options_.min_range;
  decode.max_range = options_.max_range;
  decoder_ = std::make_unique<velodyne::PacketDecoder>(
      velodyne::calibrationFor(detection_.model, options_.calibration_xml), decode);
  frames_ = std::make_unique<velodyne::FrameAssembler>(
      *decoder_, velodyne::kMaxFrameGapS, velodyne::cutAzimuth(options_.cut_angle_deg));
}

void VelodyneScanDecoder::add(const VelodyneScanMessage& message, std::vector<Scan>& done,
                              std::map<std::string, std::int64_t>& dropped) {
  if (message.packets.empty()) return;
  if (!decoder_) start(message);
  for (const auto& packet : message.packets) {
    const auto problem = decoder_->decode(packet.data.data(), packet.data.size(), decoded_);
    if (problem != velodyne::PacketProblem::kNone) {
      ++dropped[kDropScanPacketBad];
      continue;
    }
    const std::int64_t t =
        options_.capture_clock
            ? packet.stamp_ns -
                  static_cast<std::int64_t>(
                      velodyne::packetPeriod(decoder_->model(), decoded_.dual()) * 1e9)
            : clock_.place(decoded_.timestamp_us, packet.stamp_ns, true);
    if (have_last_ && t <= last_ns_) {
      ++dropped[kDropScanPacketBackwards];
      continue;
    }
    have_last_ = true;
    last_ns_ = t;
    ++packets_;
    if (decoded_.counts.no_return > 0) dropped[kDropPointsNoReturn] += decoded_.counts.no_return;
    if (decoded_.counts.out_of_range > 0) {
      dropped[kDropPointsRange] += decoded_.counts.out_of_range;
    }
    if (decoded_.counts.identical_second > 0) {
      dropped[kDropPointsDualIdentical] += decoded_.counts.identical_second;
    }
    frames_->add(decoded_, t, done);
  }
}

void VelodyneScanDecoder::flush(std::vector<Scan>& done) {
  if (frames_) frames_->flush(done);
}

}  // namespace storey
