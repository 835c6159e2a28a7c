#include "sim/raycaster.h"

#include <embree3/rtcore.h>

#include <string>

#include "common/error.h"

namespace storey::sim {

struct RayCaster::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<std::uint32_t> triangle_of_primitive;  ///< Embree primID -> mesh triangle
};

namespace {
void check(RTCDevice device, const char* what) {
  const RTCError error = rtcGetDeviceError(device);
  if (error != RTC_ERROR_NONE)
    throw Error(std::string("simulator: Embree failed to ") + what + " (error " +
                std::to_string(static_cast<int>(error)) + ")");
}
}  // namespace

RayCaster::RayCaster(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw Error("simulator: cannot create an Embree device");
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const auto& vertices = mesh.vertices();
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertices.size()));
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    v[3 * i] = static_cast<float>(vertices[i].x());
    v[3 * i + 1] = static_cast<float>(vertices[i].y());
    v[3 * i + 2] = static_cast<float>(vertices[i].z());
  }
  const auto& triangles = mesh.triangles();
  for (std::uint32_t i = 0; i < triangles.size(); ++i)
    if (returnsLight(triangles[i].surface)) impl_->triangle_of_primitive.push_back(i);
  auto* index = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), impl_->triangle_of_primitive.size()));
  for (std::size_t k = 0; k < impl_->triangle_of_primitive.size(); ++k) {
    const Triangle& t = triangles[impl_->triangle_of_primitive[k]];
    for (int c = 0; c < 3; ++c) index[3 * k + c] = t.v[c];
  }
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
  check(impl_->device, "build the ray-casting scene");
}

RayCaster::~RayCaster() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

void RayCaster::cast16(const Eigen::Vector3f origins[16], const Eigen::Vector3f directions[16],
                       float max_range, RayHit hits[16]) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // one firing: one origin, close directions
  RTCRayHit16 rh;
  alignas(64) int valid[16];  // Embree reads the mask with 64-byte aligned loads
  for (int i = 0; i < 16; ++i) {
    valid[i] = -1;
    rh.ray.org_x[i] = origins[i].x();
    rh.ray.org_y[i] = origins[i].y();
    rh.ray.org_z[i] = origins[i].z();
    rh.ray.dir_x[i] = directions[i].x();
    rh.ray.dir_y[i] = directions[i].y();
    rh.ray.dir_z[i] = directions[i].z();
    rh.ray.tnear[i] = 0.0f;
    rh.ray.tfar[i] = max_range;
    rh.ray.time[i] = 0.0f;
    rh.ray.mask[i] = 0xFFFFFFFFu;
    rh.ray.id[i] = static_cast<unsigned>(i);
    rh.ray.flags[i] = 0;
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, impl_->scene, &context, &rh);
  for (int i = 0; i < 16; ++i) {
    RayHit& hit = hits[i];
    if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
      hit = RayHit();
      continue;
    }
    hit.distance = rh.ray.tfar[i];
    hit.triangle = impl_->triangle_of_primitive[rh.hit.primID[i]];
    const Eigen::Vector3f n(rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]);
    const float norm = n.norm();
    hit.cos_incidence = norm > 0.0f ? std::abs(n.dot(directions[i])) / norm : 1.0f;
  }
}

}  // namespace storey::sim
