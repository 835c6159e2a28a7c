#pragma once
/// Embree ray caster over the returning surfaces of a mesh (glass is left
/// out, so rays pass through it). Safe to call from several threads.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "sim/mesh.h"

namespace storey::sim {

struct RayHit {
  float distance =
      std::numeric_limits<float>::infinity();  ///< along the unit direction [m]; inf = none
  std::uint32_t triangle = 0;                  ///< index into TriangleMesh::triangles()
  float cos_incidence = 1.0f;  ///< |cos| of the angle between ray and surface normal
};

class RayCaster {
 public:
  explicit RayCaster(const TriangleMesh& mesh);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  /// Casts 16 rays (unit directions) up to max_range.
  void cast16(const Eigen::Vector3f origins[16], const Eigen::Vector3f directions[16],
              float max_range, RayHit hits[16]) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace storey::sim
