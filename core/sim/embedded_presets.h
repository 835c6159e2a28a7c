#pragma once
/// Building presets compiled into the binary: generated at build time from
/// resources/buildings/*.yaml by embed_presets.cmake. Internal to core/sim.
#include <cstddef>

namespace storey::sim::detail {

struct EmbeddedPreset {
  const char* name;  ///< file name without .yaml
  const char* text;  ///< YAML text (not NUL-terminated; use size)
  std::size_t size;
};

extern const EmbeddedPreset kEmbeddedPresets[];
extern const std::size_t kEmbeddedPresetCount;

}  // namespace storey::sim::detail
