#include "io/fault_log.h"

#include <iomanip>
#include <sstream>

#include "common/log.h"

namespace storey {

void FaultLog::add(const std::string& kind, const FaultEvent& event, const std::string& what,
                   const std::string& handling) {
  FaultKindSummary& summary = kinds_[kind];
  if (summary.count == 0) {
    std::ostringstream os;
    os << std::fixed << std::setprecision(2) << what << " at " << event.time << " s into the log ("
       << event.detail << "): " << handling << "; every one is counted in report.json (faults."
       << kind << ")";
    logWarning(os.str());
  }
  ++summary.count;
  summary.total_duration += event.duration;
  if (summary.first.size() < kKeptEvents) summary.first.push_back(event);
}

std::int64_t FaultLog::count(const std::string& kind) const {
  const auto it = kinds_.find(kind);
  return it == kinds_.end() ? 0 : it->second.count;
}

}  // namespace storey
