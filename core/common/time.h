#pragma once
/// Time conventions: integer nanoseconds at I/O borders, double seconds in algorithms.
#include <cmath>
#include <cstdint>

namespace storey {

inline double nsToSeconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }
inline std::int64_t secondsToNs(double s) { return static_cast<std::int64_t>(std::llround(s * 1e9)); }

}  // namespace storey
