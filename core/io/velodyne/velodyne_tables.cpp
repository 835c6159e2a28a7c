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
    -30.67, -9.33, -29.33, -8.00, -28.00, -6.67, -26.67, -5.33, -25.33, -4.00, -24.00,
    -2.67,  -22.67, -1.33, -21.33, 0.00,  -20.00, 1.33,  -18.67, 2.67,  -17.33, 4.00,
    -16.00, 5.33,  -14.67, 6.67,  -13.33, 8.00,  -12.00, 9.33,  -10.67, 10.67};

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
  return model == Model::kVlp16 ? "VLP-16" : "HDL-32E";
}

const char* toString(ReturnMode mode) {
  switch (mode) {
    case ReturnMode::kStrongest: return "strongest return";
    case ReturnMode::kLast: return "last return";
    case ReturnMode::kDual: return "dual return";
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
  if (model == Model::kVlp16) {
    for (double e : kVlp16ElevationDeg) c.lasers.push_back(Laser{e, 0.0, 0.0, 0});
  } else {
    for (double e : kHdl32eElevationDeg) c.lasers.push_back(Laser{e, 0.0, 0.0, 0});
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
  const std::size_t lasers = model == Model::kVlp16 ? 16 : 32;
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
  for (std::size_t i = 0; i < lasers; ++i) {
    c.lasers.push_back(Laser{vert[i], rot[i], i < dist.size() ? dist[i] * 0.01 : 0.0, 0});
  }
  const auto lsb = tagValues(text, "distLSB_", path);
  if (!lsb.empty() && lsb.front() > 0.0) c.distance_resolution_m = lsb.front() * 0.01;
  assignRings(c);
  return c;
}

}  // namespace storey::velodyne
