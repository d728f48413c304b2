#pragma once
// Direct irradiance on patches from the scene's point, spot and directional
// lights, with Embree shadow rays from every member sample of a patch
// (area-weighted), so a patch half in shadow gets half the light. Point and
// spot lights are integrated over the polygons each sample carries (the
// solid angle they subtend), not evaluated at the sample's point.
// b_c = albedo_c * E_c is the light leaving each patch after the first hit,
// the vector the multi-bounce matrix multiplies.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "patches/patch_set.h"
#include "raytrace/ray_tracer.h"
#include "runtime/area_light_cache.h"
#include "runtime/area_lights.h"
#include "runtime/carried_polygon_frames.h"
#include "runtime/shadow_budget.h"
#include "scene/scene.h"

namespace bounce {

// Irradiance (per colour channel) at each patch from point, spot and
// directional lights, and from `area` lights (emissive triangles) with
// `area_strata` x `area_strata` shadow rays per sample and light.
std::vector<glm::vec3> direct_irradiance(const RayTracer& tracer, const SampleSet& samples,
                                         const PatchSet& patches, const std::vector<Light>& lights,
                                         const std::vector<AreaLight>& area = {},
                                         int area_strata = kAreaStrata);
// The same into caller-owned memory (e.g. a frame graph's arena), one entry
// per patch (throws bounce::Error otherwise). `sample_irradiance`, when not
// empty (one entry per sample), receives each member sample's own
// irradiance, of which a patch's is the area-weighted mean (samples of no
// patch are left as they are).
void direct_irradiance(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
                       const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                       int area_strata, std::span<glm::vec3> irradiance,
                       std::span<glm::vec3> sample_irradiance = {});
// The same with the carried polygons' frames computed beforehand
// (carried_polygon_frames(samples), one per entry of samples.carried), for
// callers that light the same samples every frame. Throws bounce::Error when
// the counts differ and a point or spot light needs them. `area_cache` (if
// given) keeps the samples' light from the area lights between calls
// (runtime/area_light_cache.h): it must be used with these samples only.
// `shadows` (if given) spreads the samples' shadow rays to point, spot and
// directional lights over its frames while a light moves, one batch per
// patch (runtime/shadow_budget.h); the rays of polygons large enough to take
// their own are traced every frame. Use it with these samples only.
void direct_irradiance(const RayTracer& tracer, const SampleSet& samples,
                       std::span<const CarriedPolygonFrame> frames, const PatchSet& patches,
                       const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                       int area_strata, std::span<glm::vec3> irradiance,
                       std::span<glm::vec3> sample_irradiance = {},
                       AreaLightCache* area_cache = nullptr, ShadowBudget* shadows = nullptr);

// Irradiance (per colour channel) at one surface point p with unit normal n
// (the side that receives), shadow rays included, for callers that shade
// other points (camera pixels). `seed` makes the area lights' jitter
// reproducible per point.
glm::vec3 irradiance_at(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                        const std::vector<Light>& lights, const std::vector<AreaLight>& area = {},
                        int area_strata = kAreaStrata, std::uint64_t seed = 0);

// A spot light's cones, for the smoothstep between them (1 for other lights).
struct SpotCone {
  explicit SpotCone(const Light& light)
      : spot(light.type == Light::Type::Spot),
        axis(glm::normalize(light.direction)),
        cos_inner(std::cos(glm::radians(light.spot_inner_deg))),
        cos_outer(std::cos(glm::radians(light.spot_outer_deg))) {}
  // For the unit direction from the light towards the receiver.
  float factor(const glm::vec3& from_light_dir) const {
    if (!spot) return 1.0f;
    const float c = glm::dot(from_light_dir, axis);
    const float t =
        std::clamp((c - cos_outer) / std::max(1e-6f, cos_inner - cos_outer), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
  }
  bool spot;
  glm::vec3 axis;
  float cos_inner, cos_outer;
};

// The light one point, spot or directional light sends to a surface point if
// nothing is in the way, and the shadow ray that decides whether something
// is. Made once per light, so that the per-point part (at()) is a few
// multiply-adds: callers that light many points batch the rays.
class LightReach {
 public:
  explicit LightReach(const Light& light);
  // For point p with unit normal n (the side that receives); `eps` lifts the
  // ray's origin off the surface along n. False when p faces away or lies
  // outside a spot's cone; else `ray` and `value` (the unshadowed
  // irradiance) are written, field by field, so that a caller filling
  // arrays of rays writes them in place. (Returned in a struct and copied,
  // they went through the stack in small stores read back as wide loads,
  // and every read waited on the stores: a third of the time lighting
  // Sponza's near sources.)
  bool at(const glm::vec3& p, const glm::vec3& n, float eps, ShadowRay& ray,
          glm::vec3& value) const {
    const glm::vec3 origin = p + eps * n;
    if (directional_) {
      const float cos_n = glm::dot(n, to_light_);
      if (!(cos_n > 0.0f)) return false;
      ray.origin = origin;
      ray.direction = to_light_;
      ray.t_near = 0.0f;
      ray.t_far = std::numeric_limits<float>::infinity();
      value = power_ * cos_n;
      return true;
    }
    const glm::vec3 d = position_ - origin;
    const float r2 = glm::dot(d, d);
    if (!(r2 > 0.0f)) return false;
    const glm::vec3 dir = d / std::sqrt(r2);
    const float cos_n = glm::dot(n, dir);
    if (!(cos_n > 0.0f)) return false;
    const float spot = cone_.factor(-dir);
    if (!(spot > 0.0f)) return false;
    // The segment to the light, stopping just short of it.
    ray.origin = origin;
    ray.direction = d;
    ray.t_near = 0.0f;
    ray.t_far = 1.0f - 1e-4f;
    value = power_ * spot * cos_n / r2;
    return true;
  }
  const SpotCone& cone() const { return cone_; }

 private:
  bool directional_ = false;
  glm::vec3 to_light_{0.0f}, position_{0.0f}, power_{0.0f};
  SpotCone cone_;
};

// b = albedo * E per patch and channel.
std::vector<glm::vec3> first_bounce(const PatchSet& patches,
                                    const std::vector<glm::vec3>& irradiance);

// A fixed set of test lights for error figures that do not depend on the
// scene's own lights: the scene's lights, four unit point lights at
// centre + extent * (+-0.2, 0.2, +-0.2), then one unit sun (directional
// light) per entry of kEvaluationSuns, elevation above the horizon of the
// scene camera's up vector and azimuth around it. (The bake adds the emissive
// triangles, if any, as one more.)
inline constexpr std::size_t kEvaluationPointLights = 4;
inline constexpr std::pair<float, float> kEvaluationSuns[] = {
    {75.0f, 30.0f}, {45.0f, 0.0f}, {45.0f, 90.0f}, {45.0f, 180.0f}, {45.0f, 270.0f}};
std::vector<Light> evaluation_lights(const Scene& scene);

}  // namespace bounce
