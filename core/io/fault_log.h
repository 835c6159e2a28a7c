#pragma once
/// Faults found in a log while it is read (the run goes on): each kind
/// counted with the times of its first events, for report.json's "faults"
/// section; the first event of a kind is one warning line (docs/faults.md).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace storey {

/// Fault kinds (keys of FaultLog::kinds()).
inline constexpr const char* kFaultImuSpike = "imu_spike";
inline constexpr const char* kFaultImuGap = "imu_gap";
inline constexpr const char* kFaultLidarGap = "lidar_gap";
inline constexpr const char* kFaultImuSaturation = "imu_saturation";
inline constexpr const char* kFaultLidarOccluded = "lidar_occluded";
inline constexpr const char* kFaultClockJump = "clock_jump";
inline constexpr const char* kFaultTimeOffset = "time_offset";  ///< found by the odometry
inline constexpr const char* kFaultDuplicates = "duplicate_messages";
inline constexpr const char* kFaultOutOfOrder = "out_of_order_messages";
inline constexpr const char* kFaultNotFinite = "not_finite_values";

struct FaultEvent {
  double time = 0.0;  ///< since the log's first message [s]
  double duration =
      0.0;  ///< gaps, saturation, occlusion: the time without usable data [s]; 0 otherwise
  std::string detail;  ///< what was seen, for the warning and the report
};

struct FaultKindSummary {
  std::int64_t count = 0;
  double total_duration = 0.0;    ///< [s]
  std::vector<FaultEvent> first;  ///< the first FaultLog::kKeptEvents events
};

class FaultLog {
 public:
  static constexpr std::size_t kKeptEvents = 50;

  /// Records an event of `kind`. The first one of a kind is logged as a
  /// warning: "<what> at T s into the log (<detail>): <handling>; ...".
  void add(const std::string& kind, const FaultEvent& event, const std::string& what,
           const std::string& handling);
  const std::map<std::string, FaultKindSummary>& kinds() const { return kinds_; }
  std::int64_t count(const std::string& kind) const;

 private:
  std::map<std::string, FaultKindSummary> kinds_;
};

}  // namespace storey
