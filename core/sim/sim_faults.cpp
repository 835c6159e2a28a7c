#include "sim/sim_faults.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "common/error.h"

namespace storey::sim {
namespace {

double parseNumber(const std::string& number, double& value) {
  std::size_t used = 0;
  try {
    value = std::stod(number, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  return used != 0 && used == number.size() && std::isfinite(value);
}

double parseSeconds(const std::string& number, const std::string& text) {
  double value = 0.0;
  if (number.empty() || number[0] == '+' || number[0] == '-' || !parseNumber(number, value) ||
      value < 0.0)
    throw Error("--fault '" + text + "': '" + number + "' is not a time >= 0 in seconds");
  return value;
}

const char* kindName(SimFaultKind kind) {
  switch (kind) {
    case SimFaultKind::kImuSpike:
      return "imu_spike";
    case SimFaultKind::kImuGap:
      return "imu_gap";
    case SimFaultKind::kLidarGap:
      return "lidar_gap";
    case SimFaultKind::kImuSaturation:
      return "imu_saturation";
    case SimFaultKind::kOcclusion:
      return "occlusion";
    case SimFaultKind::kImuClockJump:
      return "imu_clock_jump";
    case SimFaultKind::kLidarClockJump:
      return "lidar_clock_jump";
    case SimFaultKind::kDuplicate:
      return "duplicate";
    case SimFaultKind::kReorder:
      return "reorder";
    case SimFaultKind::kNan:
      return "nan";
  }
  return "?";
}

bool isClockJump(SimFaultKind kind) {
  return kind == SimFaultKind::kImuClockJump || kind == SimFaultKind::kLidarClockJump;
}

constexpr const char* kFaultList =
    "imu_spike@T, imu_gap@T+D, lidar_gap@T+D, imu_saturation@T+D, occlusion@T+D, "
    "duplicate@T+D, reorder@T+D, nan@T+D, imu_clock_jump@T+S, lidar_clock_jump@T+S";

}  // namespace

SimFault parseSimFault(const std::string& text) {
  const std::size_t at = text.find('@');
  const std::string kind = text.substr(0, at);
  SimFault fault;
  bool known = false;
  for (SimFaultKind k : {SimFaultKind::kImuSpike, SimFaultKind::kImuGap, SimFaultKind::kLidarGap,
                         SimFaultKind::kImuSaturation, SimFaultKind::kOcclusion,
                         SimFaultKind::kImuClockJump, SimFaultKind::kLidarClockJump,
                         SimFaultKind::kDuplicate, SimFaultKind::kReorder, SimFaultKind::kNan}) {
    if (kind == kindName(k)) {
      fault.kind = k;
      known = true;
    }
  }
  if (!known)
    throw Error("--fault '" + text + "': unknown fault '" + kind + "' (" + kFaultList + ")");
  if (at == std::string::npos) throw Error("--fault '" + text + "': expected " + kind + "@T");
  const std::string when = text.substr(at + 1);
  if (isClockJump(fault.kind)) {
    const std::size_t sign = when.find_first_of("+-", 1);
    if (sign == std::string::npos)
      throw Error("--fault '" + text + "': expected " + kind +
                  "@T+S or @T-S (start and the stamps' step in seconds)");
    fault.time = parseSeconds(when.substr(0, sign), text);
    if (!parseNumber(when.substr(sign), fault.step) || fault.step == 0.0 ||
        when.substr(sign + 1).find_first_of("+-") == 0)
      throw Error("--fault '" + text + "': '" + when.substr(sign) +
                  "' is not a step in seconds other than 0");
    return fault;
  }
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
  os << kindName(fault.kind) << '@' << fault.time;
  if (isClockJump(fault.kind)) {
    os << (fault.step >= 0.0 ? "+" : "") << fault.step;
  } else if (fault.kind != SimFaultKind::kImuSpike) {
    os << '+' << fault.duration;
  }
  return os.str();
}

SampleFaults imuSampleFaults(const std::vector<SimFault>& faults,
                             const std::vector<double>& stamps) {
  SampleFaults out;
  out.drop.assign(stamps.size(), 0);
  out.spike.assign(stamps.size(), 0);
  out.saturate.assign(stamps.size(), 0);
  out.shift_ns.assign(stamps.size(), 0);
  out.duplicate.assign(stamps.size(), 0);
  out.late.assign(stamps.size(), 0);
  out.nan.assign(stamps.size(), 0);
  for (const SimFault& f : faults) {
    const auto first = std::lower_bound(stamps.begin(), stamps.end(), f.time);
    const auto index = [&](auto it) { return static_cast<std::size_t>(it - stamps.begin()); };
    std::size_t in_window = 0;  // samples of this fault's window so far
    const auto eachInWindow = [&](auto&& apply) {
      for (auto it = first; it != stamps.end() && *it <= f.time + f.duration; ++it)
        apply(index(it), in_window++);
    };
    if (f.kind == SimFaultKind::kDuplicate) {
      eachInWindow([&](std::size_t i, std::size_t) { out.duplicate[i] = 1; });
    } else if (f.kind == SimFaultKind::kReorder) {
      eachInWindow([&](std::size_t i, std::size_t n) {
        if (n % 2 == 0 && i + 1 < stamps.size()) out.late[i] = 1;
      });
    } else if (f.kind == SimFaultKind::kNan) {
      eachInWindow([&](std::size_t i, std::size_t n) {
        if (n % 40 == 0) out.nan[i] = 1;
      });
    } else if (f.kind == SimFaultKind::kImuSpike) {
      if (first != stamps.end()) out.spike[index(first)] = 1;
    } else if (f.kind == SimFaultKind::kImuGap || f.kind == SimFaultKind::kImuSaturation) {
      std::vector<char>& flags = f.kind == SimFaultKind::kImuGap ? out.drop : out.saturate;
      for (auto it = first; it != stamps.end() && *it <= f.time + f.duration; ++it)
        flags[index(it)] = 1;
    } else if (f.kind == SimFaultKind::kImuClockJump) {
      const auto step = static_cast<std::int64_t>(std::llround(f.step * 1e9));
      for (auto it = first; it != stamps.end(); ++it) out.shift_ns[index(it)] += step;
    }
  }
  return out;
}

bool inFault(const std::vector<SimFault>& faults, SimFaultKind kind, double time) {
  return std::any_of(faults.begin(), faults.end(), [&](const SimFault& f) {
    return f.kind == kind && time >= f.time && time <= f.time + f.duration;
  });
}

bool inLidarGap(const std::vector<SimFault>& faults, double time) {
  return std::any_of(faults.begin(), faults.end(), [&](const SimFault& f) {
    return f.kind == SimFaultKind::kLidarGap && time >= f.time && time <= f.time + f.duration;
  });
}

bool inOcclusion(const std::vector<SimFault>& faults, double time) {
  return std::any_of(faults.begin(), faults.end(), [&](const SimFault& f) {
    return f.kind == SimFaultKind::kOcclusion && time >= f.time && time <= f.time + f.duration;
  });
}

std::int64_t lidarClockShiftNs(const std::vector<SimFault>& faults, double time) {
  std::int64_t shift = 0;
  for (const SimFault& f : faults)
    if (f.kind == SimFaultKind::kLidarClockJump && time >= f.time)
      shift += static_cast<std::int64_t>(std::llround(f.step * 1e9));
  return shift;
}

bool hasFault(const std::vector<SimFault>& faults, SimFaultKind kind) {
  return std::any_of(faults.begin(), faults.end(),
                     [&](const SimFault& f) { return f.kind == kind; });
}

}  // namespace storey::sim
