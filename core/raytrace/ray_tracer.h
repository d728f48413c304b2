#pragma once
// One Embree 3 BVH over the whole scene: closest-hit and occlusion queries.
// The device error callback is set once, here, and turns every Embree error
// into a RayTracer::EmbreeError (after the call that caused it returns).
// Queries are thread-safe; callers parallelise over their own work.
// An engine with its own visibility (shadow maps, its own ray tracer) makes
// a RayTracer from an OcclusionQuery instead: no BVH is built, and every
// shadow ray the runtime's frame casts goes to the engine.
// Alpha-masked triangles are holes where their mask cuts them away: no query
// reports a hit there (an Embree filter function, installed only when the
// scene has masks).
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "base/error.h"
#include "scene/scene.h"

namespace bounce {

struct Hit {
  bool hit = false;
  float t = std::numeric_limits<float>::infinity();
  std::uint32_t triangle = 0;
  glm::vec3 geometric_normal{0.0f};  // unit length, as the triangle's winding gives it
};

struct ShadowRay {
  glm::vec3 origin;
  glm::vec3 direction;  // need not be unit length: t is in units of it
  float t_near = 0.0f;
  float t_far = 1.0f;
};

// An engine's answer to shadow rays: blocked[k] = 1 when something lies on
// ray k between t_near and t_far (in units of its direction), else 0. Called
// from several threads at once, with batches of any size; it must not throw.
using OcclusionQuery =
    std::function<void(std::span<const ShadowRay> rays, std::span<std::uint8_t> blocked)>;

class RayTracer {
 public:
  class EmbreeError : public Error {
   public:
    using Error::Error;
  };

  explicit RayTracer(const Scene& scene);
  // Occlusion answered by `query` (which must not be empty), no BVH built.
  // The runtime's frame (Relighter: direct light on the samples, area
  // lights, the final gather's near sources) asks only occlusion; the
  // closest-hit queries, which the bake and the camera pictures need, throw
  // bounce::Error on such a tracer.
  RayTracer(const Scene& scene, OcclusionQuery query);
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  // Closest hit along origin + t*direction for t in [t_near, t_far].
  Hit intersect(const glm::vec3& origin, const glm::vec3& direction, float t_near = 0.0f,
                float t_far = std::numeric_limits<float>::infinity()) const;

  // All hits along the segment, sorted by t (at most max_hits).
  std::vector<Hit> intersect_all(const glm::vec3& origin, const glm::vec3& direction, float t_near,
                                 float t_far, std::size_t max_hits) const;

  bool occluded(const glm::vec3& origin, const glm::vec3& direction, float t_near,
                float t_far) const;

  // Batched occlusion: writes 1 for blocked rays, 0 for free ones. Uses Embree's
  // stream API (rtcOccluded1M), which pays for incoherent batches.
  void occluded(const ShadowRay* rays, std::size_t count, std::uint8_t* blocked) const;

  const Scene& scene() const { return scene_; }
  // A distance that is small against the scene (1e-6 of its diagonal): used to
  // step past a surface without skipping anything of the scene's own scale.
  float epsilon() const { return epsilon_; }

 private:
  void throw_pending_error() const;
  void require_bvh(const char* query) const;
  struct Impl;
  const Scene& scene_;
  float epsilon_ = 0.0f;
  std::unique_ptr<Impl> impl_;
};

// The first hit of a ray leaving a surface point at `origin` (already lifted
// by `offset` along its normal). A point on an edge or in a corner lies in its
// neighbours' planes: a one-sided neighbour's back met within `offset` is not
// a blocker but the plane the point stands in, so the origin moves off it,
// to its front, and the ray is cast again (up to three times). A front face
// met at t ~ 0 stays a hit: it is the neighbouring wall, seen at the edge.
// `origin` is updated; the hit point is origin + t * direction.
Hit intersect_leaving_surface(const RayTracer& tracer, glm::vec3& origin,
                              const glm::vec3& direction, float offset);

}  // namespace bounce
