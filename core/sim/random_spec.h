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

/// What `storey simulate --lidar/--imu/--motion` change in a spec (a preset,
/// a file or a random draw); empty = keep.
struct RigOverrides {
  std::string lidar;   ///< a LiDAR model: VLP-16, VLP-32C, HDL-32E, OS1-64
  std::string imu;     ///< an IMU grade, optionally at a rate: tactical, consumer@100
  std::string motion;  ///< legged or handheld
};
/// Applies the overrides: the LiDAR model keeps its mount; the IMU takes the
/// grade's figures (at its nominal rate unless one is given) and keeps its
/// mount and orientation field; a new motion takes that motion's robot
/// defaults but keeps the walking lanes and the start. storey::Error naming
/// the option for a value that is not one of the names.
void applyRigOverrides(BuildingSpec& spec, const RigOverrides& overrides);

/// "random:SEED" -> SEED; nullopt for any other text. Throws storey::Error
/// for "random:" followed by something that is not a seed.
std::optional<std::uint64_t> randomSeedOf(const std::string& name);

}  // namespace storey::sim
