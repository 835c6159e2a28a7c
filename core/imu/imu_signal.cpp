#include "imu/imu_signal.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "common/error.h"

namespace storey {
namespace {

std::string seconds(std::int64_t ns) {
  std::ostringstream os;
  os << std::fixed << std::setprecision(6) << nsToSeconds(ns) << " s";
  return os.str();
}

ImuKnot knotAt(const ImuSample& sample, std::int64_t start_ns) {
  return ImuKnot{nsToSeconds(sample.stamp_ns - start_ns), sample.gyro, sample.accel};
}

/// Linear interpolation between samples a and b (a.stamp_ns < stamp_ns < b.stamp_ns).
ImuKnot interpolate(const ImuSample& a, const ImuSample& b, std::int64_t stamp_ns,
                    std::int64_t start_ns) {
  const double s =
      static_cast<double>(stamp_ns - a.stamp_ns) / static_cast<double>(b.stamp_ns - a.stamp_ns);
  return ImuKnot{nsToSeconds(stamp_ns - start_ns), a.gyro + s * (b.gyro - a.gyro),
                 a.accel + s * (b.accel - a.accel)};
}

void checkSample(const ImuSample& sample) {
  if (!sample.isFinite()) {
    throw Error("IMU sample at " + seconds(sample.stamp_ns) +
                " is not finite (NaN or infinite gyro or accel)");
  }
}

}  // namespace

ImuSignal sliceImuSignal(const ImuSample* samples, std::size_t count, std::int64_t start_ns,
                         std::int64_t end_ns) {
  if (start_ns >= end_ns) {
    throw Error("IMU interval [" + seconds(start_ns) + ", " + seconds(end_ns) +
                "] is empty: its start must be before its end");
  }
  if (count == 0 || samples[0].stamp_ns > start_ns || samples[count - 1].stamp_ns < end_ns) {
    const std::string have = count == 0 ? std::string("no IMU samples")
                                        : "IMU samples cover [" + seconds(samples[0].stamp_ns) +
                                              ", " + seconds(samples[count - 1].stamp_ns) + "]";
    throw Error(have + " but [" + seconds(start_ns) + ", " + seconds(end_ns) +
                "] is needed: the IMU must cover every scan (wait for the next IMU sample "
                "before processing a scan)");
  }
  const auto by_stamp = [](std::int64_t t, const ImuSample& s) { return t < s.stamp_ns; };
  // first: last sample with stamp <= start_ns; last: first sample with stamp >= end_ns.
  const ImuSample* end = samples + count;
  const ImuSample* first = std::upper_bound(samples, end, start_ns, by_stamp) - 1;
  const ImuSample* last = std::lower_bound(
      first, end, end_ns, [](const ImuSample& s, std::int64_t t) { return s.stamp_ns < t; });

  ImuSignal signal;
  signal.start_ns = start_ns;
  signal.end_ns = end_ns;
  signal.knots.reserve(static_cast<std::size_t>(last - first) + 2);
  checkSample(*first);
  for (const ImuSample* s = first + 1; s <= last; ++s) {
    checkSample(*s);
    if (s->stamp_ns < (s - 1)->stamp_ns) {
      throw Error("IMU samples go back in time: " + seconds(s->stamp_ns) + " follows " +
                  seconds((s - 1)->stamp_ns));
    }
  }
  signal.knots.push_back(first->stamp_ns == start_ns
                             ? knotAt(*first, start_ns)
                             : interpolate(*first, *(first + 1), start_ns, start_ns));
  // The sample before the one at index i is the previous distinct stamp.
  const ImuSample* prev = first;
  for (const ImuSample* s = first + 1; s < last; ++s) {
    if (s->stamp_ns == prev->stamp_ns) continue;  // duplicate stamp
    signal.knots.push_back(knotAt(*s, start_ns));
    signal.knots.back().sample_spacing = nsToSeconds(s->stamp_ns - prev->stamp_ns);
    signal.knots.back().dropout = s->after_removed || s->filled || prev->filled;
    prev = s;
  }
  if (last->stamp_ns == end_ns) {
    signal.knots.push_back(knotAt(*last, start_ns));
  } else {
    // prev is the last distinct sample before end_ns (or first, which is < end_ns).
    signal.knots.push_back(interpolate(*prev, *last, end_ns, start_ns));
  }
  signal.knots.back().sample_spacing = nsToSeconds(last->stamp_ns - prev->stamp_ns);
  signal.knots.back().dropout = last->after_removed || last->filled || prev->filled;
  for (std::size_t k = 1; k < signal.knots.size(); ++k) {
    signal.max_gap = std::max(signal.max_gap, signal.knots[k].t - signal.knots[k - 1].t);
  }
  return signal;
}

}  // namespace storey
