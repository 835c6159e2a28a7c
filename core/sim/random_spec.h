#pragma once
/// A building, sensor rig and walk drawn from a seed (`storey simulate
/// random:SEED`), to measure Storey on buildings it was not tuned on
/// (docs/benchmarks.md). The ranges drawn from are in docs/simulator.md
/// ("Random buildings"). Same seed, same spec, on every platform.
#include <cstdint>
#include <optional>
#include <string>

#include "sim/building_spec.h"

namespace storey::sim {

/// The spec of random building `seed` (name "random-SEED", spec.seed = seed).
/// It is valid and generates (a draw the generator refuses is drawn again
/// from the next stream of the same seed).
BuildingSpec drawRandomSpec(std::uint64_t seed);

/// "random:SEED" -> SEED; nullopt for any other text. Throws storey::Error
/// for "random:" followed by something that is not a seed.
std::optional<std::uint64_t> randomSeedOf(const std::string& name);

}  // namespace storey::sim
