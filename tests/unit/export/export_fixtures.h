#pragma once
#include "map/map_cloud.h"

namespace storey::test {

/// A small labelled cloud with known attributes (coordinates far from the
/// origin in x to exercise the LAS offset).
inline MapCloud sampleCloud(std::size_t n = 1000) {
  MapCloud cloud;
  for (std::size_t i = 0; i < n; ++i) {
    const float f = static_cast<float>(i);
    cloud.positions.emplace_back(1000.0f + 0.0137f * f, -5.0f + 0.011f * f, 0.5f * std::sin(f));
    cloud.intensity.push_back(static_cast<float>(i % 256));
    cloud.time.push_back(1.7e9 + 0.001 * static_cast<double>(i));
    cloud.keyframe.push_back(static_cast<std::int32_t>(i / 10));
    cloud.storey.push_back(static_cast<std::int16_t>(i % 3 == 0 ? kNoStorey : i % 4));
    cloud.flags.push_back(static_cast<std::uint8_t>(i % 5 == 0 ? kMapPointStairs : 0));
  }
  return cloud;
}

}  // namespace storey::test
