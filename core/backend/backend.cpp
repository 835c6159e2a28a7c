#include "backend/backend.h"

#include "backend/odometry_backend.h"
#include "backend/srp_backend.h"

namespace storey {

std::unique_ptr<Backend> makeBackend(const BackendConfig& config) {
  config.validate();
  if (config.srp) return std::make_unique<SrpBackend>(config);
  return std::make_unique<OdometryBackend>(config.keyframes);
}

}  // namespace storey
