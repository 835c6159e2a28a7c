#include "io/velodyne/velodyne_tables.h"

#include <algorithm>
#include <fstream>
#include <numeric>
#include <sstream>

#include "common/error.h"

namespace storey::velodyne {
namespace {

// VLP-16 manual, table "Vertical Angles": laser id -> elevation [deg].
constexpr std::array<double, 16> kVlp16ElevationDeg = {
    -15.0, 1.0, -13.0, 3.0, -11.0, 5.0, -9.0, 7.0, -7.0, 9.0, -5.0, 11.0, -3.0, 13.0, -1.0, 15.0};

// HDL-32E manual, Appendix A "Vertical angles": laser id -> elevation [deg].
constexpr std::array<double, 32> kHdl32eElevationDeg = {
    -30.67, -9.33,  -29.33, -8.00,  -28.00, -6.67,  -26.67, -5.33,  -25.33, -4.00,  -24.00,
    -2.67,  -22.67, -1.33,  -21.33, 0.00,   -20.00, 1.33,   -18.67, 2.67,   -17.33, 4.00,
    -16.00, 5.33,   -14.67, 6.67,   -13.33, 8.00,   -12.00, 9.33,   -10.67, 10.67};

// VLP-32C manual, table "Vertical Angles and Azimuth Offsets": laser id ->
// elevation [deg] and azimuth offset [deg] (the offset is added to the block
// azimuth; VeloView's rotCorrection and Laser::azimuth_offset_deg are its negative).
constexpr std::array<double, 32> kVlp32cElevationDeg = {
    -25.0,  -1.0,   -1.667, -15.639, -11.31, 0.0,    -0.667, -8.843, -7.254, 0.333,  -0.333,
    -6.148, -5.333, 1.333,  0.667,   -4.0,   -4.667, 1.667,  1.0,    -3.667, -3.333, 3.333,
    2.333,  -2.667, -3.0,   7.0,     4.667,  -2.333, -2.0,   15.0,   10.333, -1.333};
constexpr std::array<double, 32> kVlp32cAzimuthOffsetDeg = {
    1.4, -4.2, 1.4, -1.4, 1.4, -1.4, 4.2, -1.4, 1.4, -4.2, 1.4, -1.4, 4.2, -1.4, 4.2, -1.4,
    1.4, -4.2, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4, 1.4, -1.4, 1.4, -4.2, 4.2, -1.4, 1.4, -1.4};

/// Values of every `<tag>` element of `text`, in order.
std::vector<double> tagValues(const std::string& text, const std::string& tag,
                              const std::string& path) {
  std::vector<double> values;
  const std::string open = "<" + tag + ">";
  for (std::size_t at = text.find(open); at != std::string::npos; at = text.find(open, at)) {
    at += open.size();
    const std::size_t end = text.find('<', at);
    try {
      values.push_back(std::stod(text.substr(at, end - at)));
    } catch (const std::exception&) {
      throw Error(path + ": <" + tag + "> at byte " + std::to_string(at) + " is not a number");
    }
  }
  return values;
}

}  // namespace

const char* toString(Model model) {
  switch (model) {
    case Model::kVlp16:
      return "VLP-16";
    case Model::kVlp32c:
      return "VLP-32C";
    case Model::kHdl32e:
      return "HDL-32E";
  }
  return "unknown Velodyne model";
}

int laserCount(Model model) {
  return model == Model::kVlp16 ? 16 : 32;
}

double laserFiringOffset(Model model, int id) {
  switch (model) {
    case Model::kVlp16:
      return id * kVlp16FiringS;
    case Model::kVlp32c:
      return (id / 2) * kVlp32cFiringS;
    case Model::kHdl32e:
      return id * kHdl32eFiringS;
  }
  return 0.0;
}

double sequencePeriod(Model model) {
  switch (model) {
    case Model::kVlp16:
      return kVlp16SequenceS;
    case Model::kVlp32c:
      return kVlp32cSequenceS;
    case Model::kHdl32e:
      return kHdl32eSequenceS;
  }
  return 0.0;
}

const char* toString(ReturnMode mode) {
  switch (mode) {
    case ReturnMode::kStrongest:
      return "strongest return";
    case ReturnMode::kLast:
      return "last return";
    case ReturnMode::kDual:
      return "dual return";
  }
  return "unknown return mode";
}

void assignRings(Calibration& calibration) {
  auto& lasers = calibration.lasers;
  std::vector<std::size_t> order(lasers.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return lasers[a].elevation_deg < lasers[b].elevation_deg;
  });
  for (std::size_t rank = 0; rank < order.size(); ++rank) {
    lasers[order[rank]].ring = static_cast<std::uint16_t>(rank);
  }
}

Calibration defaultCalibration(Model model) {
  Calibration c;
  c.model = model;
  switch (model) {
    case Model::kVlp16:
      for (double e : kVlp16ElevationDeg) c.lasers.push_back(Laser{e, 0.0, 0.0, 0});
      break;
    case Model::kVlp32c:
      for (std::size_t i = 0; i < kVlp32cElevationDeg.size(); ++i)
        c.lasers.push_back(Laser{kVlp32cElevationDeg[i], -kVlp32cAzimuthOffsetDeg[i], 0.0, 0});
      c.distance_resolution_m = 0.004;
      break;
    case Model::kHdl32e:
      for (double e : kHdl32eElevationDeg) c.lasers.push_back(Laser{e, 0.0, 0.0, 0});
      break;
  }
  assignRings(c);
  return c;
}

Calibration readVeloViewCalibration(const std::string& path, Model model) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open the Velodyne calibration file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::size_t lasers = static_cast<std::size_t>(laserCount(model));
  const auto vert = tagValues(text, "vertCorrection_", path);
  const auto rot = tagValues(text, "rotCorrection_", path);
  const auto dist = tagValues(text, "distCorrection_", path);
  if (vert.size() < lasers || rot.size() < lasers) {
    throw Error(path + ": expected VeloView calibration XML with at least " +
                std::to_string(lasers) + " <vertCorrection_> and <rotCorrection_> entries for " +
                toString(model) + ", found " + std::to_string(vert.size()));
  }
  Calibration c;
  c.model = model;
  c.distance_resolution_m = defaultCalibration(model).distance_resolution_m;
  for (std::size_t i = 0; i < lasers; ++i) {
    c.lasers.push_back(Laser{vert[i], rot[i], i < dist.size() ? dist[i] * 0.01 : 0.0, 0});
  }
  const auto lsb = tagValues(text, "distLSB_", path);
  if (!lsb.empty() && lsb.front() > 0.0) c.distance_resolution_m = lsb.front() * 0.01;
  assignRings(c);
  return c;
}

Calibration calibrationFor(Model model, const std::string& calibration_xml) {
  return calibration_xml.empty() ? defaultCalibration(model)
                                 : readVeloViewCalibration(calibration_xml, model);
}

}  // namespace storey::velodyne
