#include "sim/sim_faults.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"

namespace storey::sim {
namespace {

double parseSeconds(const std::string& number, const std::string& text) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != number.size() || !std::isfinite(value) || value < 0.0)
    throw Error("--fault '" + text + "': '" + number + "' is not a time >= 0 in seconds");
  return value;
}

}  // namespace

SimFault parseSimFault(const std::string& text) {
  const std::size_t at = text.find('@');
  const std::string kind = text.substr(0, at);
  SimFault fault;
  if (kind == "imu_spike") {
    fault.kind = SimFaultKind::kImuSpike;
  } else if (kind == "imu_gap") {
    fault.kind = SimFaultKind::kImuGap;
  } else if (kind == "lidar_gap") {
    fault.kind = SimFaultKind::kLidarGap;
  } else {
    throw Error("--fault '" + text + "': unknown fault '" + kind +
                "' (imu_spike@T, imu_gap@T+D, lidar_gap@T+D)");
  }
  if (at == std::string::npos) throw Error("--fault '" + text + "': expected " + kind + "@T");
  const std::string when = text.substr(at + 1);
  const std::size_t plus = when.find('+');
  fault.time = parseSeconds(when.substr(0, plus), text);
  if (fault.kind == SimFaultKind::kImuSpike) {
    if (plus != std::string::npos)
      throw Error("--fault '" + text + "': a spike is one sample (imu_spike@T, no duration)");
  } else {
    if (plus == std::string::npos)
      throw Error("--fault '" + text + "': expected " + kind + "@T+D (start and duration)");
    fault.duration = parseSeconds(when.substr(plus + 1), text);
  }
  return fault;
}

std::string toString(const SimFault& fault) {
  std::ostringstream os;
  os << (fault.kind == SimFaultKind::kImuSpike ? "imu_spike"
         : fault.kind == SimFaultKind::kImuGap ? "imu_gap"
                                               : "lidar_gap")
     << '@' << fault.time;
  if (fault.kind != SimFaultKind::kImuSpike) os << '+' << fault.duration;
  return os.str();
}

SampleFaults imuSampleFaults(const std::vector<SimFault>& faults,
                             const std::vector<double>& stamps) {
  SampleFaults out;
  out.drop.assign(stamps.size(), 0);
  out.spike.assign(stamps.size(), 0);
  for (const SimFault& f : faults) {
    const auto first = std::lower_bound(stamps.begin(), stamps.end(), f.time);
    if (f.kind == SimFaultKind::kImuSpike) {
      if (first != stamps.end()) out.spike[static_cast<std::size_t>(first - stamps.begin())] = 1;
    } else if (f.kind == SimFaultKind::kImuGap) {
      for (auto it = first; it != stamps.end() && *it <= f.time + f.duration; ++it)
        out.drop[static_cast<std::size_t>(it - stamps.begin())] = 1;
    }
  }
  return out;
}

bool inLidarGap(const std::vector<SimFault>& faults, double time) {
  return std::any_of(faults.begin(), faults.end(), [&](const SimFault& f) {
    return f.kind == SimFaultKind::kLidarGap && time >= f.time && time <= f.time + f.duration;
  });
}

}  // namespace storey::sim
