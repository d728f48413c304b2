#include "raytrace/ray_tracer.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <string>

namespace bounce {

namespace {

const char* error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

// Rejects hits on the cut-away parts of alpha-masked triangles, so that
// every query (closest hit, occlusion, streams) sees through them. Embree
// passes the hit's barycentric coordinates; the scene looks its mask up there.
void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* scene = static_cast<const Scene*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned tri = RTCHitN_primID(args->hit, args->N, i);
    if (!scene->solid_at(tri, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i)))
      args->valid[i] = 0;
  }
}

}  // namespace

struct RayTracer::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // Embree reports errors through a callback that must not throw; we record
  // the first one and throw from our own frame right after the call.
  mutable std::mutex error_mutex;
  mutable std::string pending_error;
  mutable std::atomic<bool> has_error{false};
  // Set for a tracer whose occlusion the engine answers (no device, no BVH).
  OcclusionQuery query;

  static void on_error(void* user, RTCError code, const char* message) {
    auto* self = static_cast<Impl*>(user);
    std::lock_guard lock(self->error_mutex);
    if (!self->has_error) {
      self->pending_error =
          std::string(error_name(code)) + (message ? std::string(": ") + message : "");
      self->has_error = true;
    }
  }
};

RayTracer::RayTracer(const Scene& scene) : scene_(scene), impl_(std::make_unique<Impl>()) {
  epsilon_ = 1e-6f * std::max(1e-20f, glm::length(scene.bounds().extent()));
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device)
    throw EmbreeError(
        "embree", std::string("cannot create device: ") + error_name(rtcGetDeviceError(nullptr)));
  rtcSetDeviceErrorFunction(impl_->device, &Impl::on_error, impl_.get());

  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);

  RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                               RTC_FORMAT_FLOAT3, 3 * sizeof(float),
                                                               scene.positions.size()));
  auto* indices = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                              3 * sizeof(unsigned), scene.triangles.size()));
  throw_pending_error();
  for (std::size_t i = 0; i < scene.positions.size(); ++i) {
    vertices[3 * i + 0] = scene.positions[i].x;
    vertices[3 * i + 1] = scene.positions[i].y;
    vertices[3 * i + 2] = scene.positions[i].z;
  }
  for (std::size_t i = 0; i < scene.triangles.size(); ++i) {
    indices[3 * i + 0] = scene.triangles[i].x;
    indices[3 * i + 1] = scene.triangles[i].y;
    indices[3 * i + 2] = scene.triangles[i].z;
  }
  // Only a scene with masks pays for a filter call per hit; without one the
  // BVH and every answer are those of plain triangles.
  if (scene.has_masks()) {
    rtcSetGeometryUserData(geom, const_cast<Scene*>(&scene));
    rtcSetGeometryIntersectFilterFunction(geom, &alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geom, &alpha_filter);
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(impl_->scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(impl_->scene);
  throw_pending_error();
}

RayTracer::RayTracer(const Scene& scene, OcclusionQuery query)
    : scene_(scene), impl_(std::make_unique<Impl>()) {
  if (!query) throw Error("ray tracer", "the engine's occlusion query is empty");
  epsilon_ = 1e-6f * std::max(1e-20f, glm::length(scene.bounds().extent()));
  impl_->query = std::move(query);
}

RayTracer::~RayTracer() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

void RayTracer::throw_pending_error() const {
  if (!impl_->has_error) return;
  std::lock_guard lock(impl_->error_mutex);
  throw EmbreeError("embree", impl_->pending_error);
}

void RayTracer::require_bvh(const char* query) const {
  if (impl_->scene) return;
  throw Error("ray tracer",
              std::string(query) +
                  " needs the scene's own BVH; this tracer passes shadow rays to the engine's "
                  "occlusion query and answers nothing else");
}

static RTCRayHit make_rayhit(const glm::vec3& o, const glm::vec3& d, float t_near, float t_far) {
  RTCRayHit rh{};
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x;
  rh.ray.dir_y = d.y;
  rh.ray.dir_z = d.z;
  rh.ray.tnear = t_near;
  rh.ray.tfar = t_far;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rh;
}

Hit RayTracer::intersect(const glm::vec3& origin, const glm::vec3& direction, float t_near,
                         float t_far) const {
  require_bvh("a closest-hit query");
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh = make_rayhit(origin, direction, t_near, t_far);
  rtcIntersect1(impl_->scene, &ctx, &rh);
  throw_pending_error();
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.triangle = rh.hit.primID;
  h.geometric_normal = glm::normalize(glm::vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z));
  return h;
}

std::vector<Hit> RayTracer::intersect_all(const glm::vec3& origin, const glm::vec3& direction,
                                          float t_near, float t_far, std::size_t max_hits) const {
  // Walk the segment hit by hit. Re-starting just past each hit can skip a
  // triangle that shares the hit point (an edge), but never reports one twice:
  // we also exclude the triangle just hit by comparing ids.
  std::vector<Hit> hits;
  const float step = epsilon_ / std::max(1e-30f, glm::length(direction));
  float t = t_near;
  while (hits.size() < max_hits && t < t_far) {
    Hit h = intersect(origin, direction, t, t_far);
    if (!h.hit) break;
    if (hits.empty() || hits.back().triangle != h.triangle) hits.push_back(h);
    t = h.t + step;
  }
  return hits;
}

bool RayTracer::occluded(const glm::vec3& origin, const glm::vec3& direction, float t_near,
                         float t_far) const {
  if (impl_->query) {
    const ShadowRay ray{origin, direction, t_near, t_far};
    std::uint8_t blocked = 0;
    impl_->query({&ray, 1}, {&blocked, 1});
    return blocked != 0;
  }
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray = make_rayhit(origin, direction, t_near, t_far).ray;
  rtcOccluded1(impl_->scene, &ctx, &ray);
  throw_pending_error();
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on a blocked ray
}

void RayTracer::occluded(const ShadowRay* rays, std::size_t count, std::uint8_t* blocked) const {
  if (impl_->query) {
    impl_->query({rays, count}, {blocked, count});
    return;
  }
  constexpr std::size_t kChunk = 256;
  RTCRay batch[kChunk];
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  for (std::size_t start = 0; start < count; start += kChunk) {
    const std::size_t n = std::min(kChunk, count - start);
    // Each field written in place: a whole RTCRayHit built and copied went
    // through the stack in stores that the copy's wide loads waited on.
    for (std::size_t k = 0; k < n; ++k) {
      const ShadowRay& r = rays[start + k];
      RTCRay& ray = batch[k];
      ray.org_x = r.origin.x;
      ray.org_y = r.origin.y;
      ray.org_z = r.origin.z;
      ray.tnear = r.t_near;
      ray.dir_x = r.direction.x;
      ray.dir_y = r.direction.y;
      ray.dir_z = r.direction.z;
      ray.time = 0.0f;
      ray.tfar = r.t_far;
      ray.mask = 0xFFFFFFFFu;
      ray.id = 0;
      ray.flags = 0;
    }
    rtcOccluded1M(impl_->scene, &ctx, batch, static_cast<unsigned>(n), sizeof(RTCRay));
    for (std::size_t k = 0; k < n; ++k) blocked[start + k] = batch[k].tfar < 0.0f ? 1 : 0;
  }
  throw_pending_error();
}

Hit intersect_leaving_surface(const RayTracer& tracer, glm::vec3& origin,
                              const glm::vec3& direction, float offset) {
  Hit hit = tracer.intersect(origin, direction);
  for (int retry = 0;
       retry < 3 && hit.hit && hit.t <= offset &&
       glm::dot(hit.geometric_normal, direction) > 0.0f && !tracer.scene().two_sided(hit.triangle);
       ++retry) {
    origin += offset * hit.geometric_normal;
    hit = tracer.intersect(origin, direction);
  }
  return hit;
}

}  // namespace bounce
