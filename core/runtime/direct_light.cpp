#include "runtime/direct_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

// Whether the segment from `origin` to a point or spot light is free.
bool sees_light(const RayTracer& tracer, const glm::vec3& origin, const Light& light) {
  return !tracer.occluded(origin, light.position - origin, 0.0f, 1.0f - 1e-4f);
}

// One sample's visibility of one light, traced at most once per frame. With
// a shadow budget (runtime/shadow_budget.h) it is kept between frames: a
// sample whose patch is not traced this frame reuses what its last trace
// found. A traced sample that did not need the ray (it faced away) is kept
// as unknown, and traced when it is needed.
class SampleShadow {
 public:
  SampleShadow() = default;  // no budget: traced when needed
  SampleShadow(std::uint8_t* kept, bool traced) : kept_(kept), traced_(traced) {}
  SampleShadow(const SampleShadow&) = delete;
  SampleShadow& operator=(const SampleShadow&) = delete;
  ~SampleShadow() {
    if (kept_ && traced_ && known_ < 0) *kept_ = kUnknown;
  }

  template <class Trace>
  bool sees(Trace&& trace) {
    if (known_ < 0) {
      if (kept_ && !traced_ && *kept_ != kUnknown) {
        known_ = *kept_;
      } else {
        known_ = trace() ? 1 : 0;
        if (kept_) *kept_ = static_cast<std::uint8_t>(known_);
      }
    }
    return known_ == 1;
  }

 private:
  static constexpr std::uint8_t kUnknown = 2;
  std::uint8_t* kept_ = nullptr;
  bool traced_ = true;
  int known_ = -1;
};

// Irradiance at point p (normal n) from one light, visibility included.
glm::vec3 from_light(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                     const LightReach& light, float eps, SampleShadow& shadow) {
  ShadowRay ray;
  glm::vec3 value;
  if (!light.at(p, n, eps, ray, value) || !shadow.sees([&] {
        return !tracer.occluded(ray.origin, ray.direction, ray.t_near, ray.t_far);
      }))
    return glm::vec3(0.0f);
  return value;
}

// Whether any light is one that direct light integrates over the carried
// polygons (point and spot lights, not directional ones).
bool has_point_or_spot_light(const std::vector<Light>& lights) {
  return std::any_of(lights.begin(), lights.end(),
                     [](const Light& l) { return l.type != Light::Type::Directional; });
}

// Solid angle of the triangle (a, b, c) seen from the origin, signed by its
// winding (Van Oosterom & Strackee 1983). The triple product is taken over
// the edge vectors, which does not cancel for small, far triangles.
double signed_solid_angle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  const double la = glm::length(a), lb = glm::length(b), lc = glm::length(c);
  const double num = glm::dot(a, glm::cross(b - a, c - a));
  const double den = la * lb * lc + glm::dot(a, b) * lc + glm::dot(a, c) * lb + glm::dot(b, c) * la;
  return 2.0 * std::atan2(num, den);
}

// A polygon that subtends more than this from a point light gets its own
// shadow rays (one per triangle of a fan about its centroid); a smaller one
// shares its sample's single ray. A misjudged smaller polygon moves at most
// 0.01 / 4 pi = 0.08% of the light's power, and at most 4 pi / 0.01 ~ 1300
// polygons facing a light (a few times that counting occluded and two-sided
// ones) can be larger, so the extra rays stay near the light, where the
// received power is concentrated and a shadow edge across one polygon matters.
constexpr float kOwnRaysSolidAngle = 0.01f;

// A polygon whose vertices all lie within this fraction of its distance from
// the light (measured from its centroid) takes the midpoint rule, area x cos /
// r^2 at its centroid, instead of the exact solid angle: the rule's relative
// error is of order (radius / distance)^2 (times a few at grazing angles),
// < 1e-3 here. Finely meshed surfaces carry ~10 such polygons per sample
// (cornell-bunny), where the exact fan's three square roots and an atan2 per
// triangle cost as much as the shadow ray.
constexpr float kMidpointRadius = 0.02f;

// Power (irradiance x area, per colour) that sample `si` receives from a
// point or spot light, integrated over the polygons it carries: for a planar
// polygon facing the light, cos / r^2 integrates to the solid angle it
// subtends, so it receives intensity x solid angle, exactly, whatever its
// distance (a point evaluation at the sample turns 1/r^2 at a sample close to
// the light into a large share of the scene's light, seed-dependent:
// docs/benchmarks.md). Visibility: see kOwnRaysSolidAngle.
glm::vec3 point_light_power(const RayTracer& tracer, const SampleSet& set,
                            std::span<const CarriedPolygonFrame> frames, std::uint32_t si,
                            const Light& light, const SpotCone& cone, float eps,
                            SampleShadow& shadow) {
  const Sample& s = set.samples[si];
  const glm::vec3 flux = light.color * light.intensity;
  // The sample's own shadow ray, traced on first use.
  auto sample_visibility = [&] {
    return shadow.sees([&] { return sees_light(tracer, s.position + eps * s.normal, light); })
               ? 1.0f
               : 0.0f;
  };
  glm::vec3 power(0.0f);
  for (std::uint32_t c = set.carried_first[si]; c < set.carried_first[si + 1]; ++c) {
    const CarriedArea& piece = set.carried[c];
    const glm::vec3* poly = &set.carried_vertices[piece.first_vertex];
    const std::uint32_t count = piece.vertex_count;
    const CarriedPolygonFrame& f = frames[c];
    if (!(f.area > 0.0f)) continue;
    const glm::vec3 to_light = light.position - f.centroid;
    // A planar polygon lies wholly in front of the light or wholly behind.
    const float facing = glm::dot(f.normal, to_light);
    if (!(facing > 0.0f)) continue;
    const float r2 = glm::dot(to_light, to_light);
    // Carried areas are the polygons' areas rescaled to add up to their
    // triangle part's (rounding); keep that total.
    const float scale = piece.area / f.area;
    float omega;
    if (f.radius2 < kMidpointRadius * kMidpointRadius * r2) {
      omega = f.area * facing / (r2 * std::sqrt(r2));
    } else {
      const glm::dvec3 l(light.position), a0 = glm::dvec3(poly[0]) - l;
      double sum = 0.0;
      for (std::uint32_t k = 1; k + 1 < count; ++k)
        sum += signed_solid_angle(a0, glm::dvec3(poly[k]) - l, glm::dvec3(poly[k + 1]) - l);
      omega = static_cast<float>(std::abs(sum));
    }
    if (omega < kOwnRaysSolidAngle) {
      const float spot = cone.spot ? cone.factor(-to_light / std::sqrt(r2)) : 1.0f;
      if (spot > 0.0f) power += flux * (omega * spot * scale * sample_visibility());
      continue;
    }
    const glm::dvec3 l(light.position), m = glm::dvec3(f.centroid) - l;
    const glm::vec3 offset = eps * f.normal;
    for (std::uint32_t k = 0; k < count; ++k) {
      const glm::vec3& b = poly[k];
      const glm::vec3& e = poly[(k + 1) % count];
      const double part = std::abs(signed_solid_angle(m, glm::dvec3(b) - l, glm::dvec3(e) - l));
      const glm::vec3 at = (f.centroid + b + e) / 3.0f;
      const float spot = cone.spot ? cone.factor(glm::normalize(at - light.position)) : 1.0f;
      if (spot > 0.0f && sees_light(tracer, at + offset, light))
        power += flux * (static_cast<float>(part) * spot * scale);
    }
  }
  return power;
}

// Each sample's irradiance from the area lights (sample si seeds its jitter
// with si).
void area_irradiance_per_sample(const RayTracer& tracer, const SampleSet& samples,
                                const std::vector<AreaLight>& area_lights, int strata,
                                std::vector<glm::vec3>& out) {
  out.clear();
  if (area_lights.empty()) return;
  std::vector<glm::vec3> p, n;
  for (const Sample& s : samples.samples) {
    p.push_back(s.position);
    n.push_back(s.normal);
  }
  area_irradiance_at_points(tracer, p, n, area_lights, strata, p.size(), out);
}

}  // namespace

std::vector<glm::vec3> direct_irradiance(const RayTracer& tracer, const SampleSet& samples,
                                         const PatchSet& patches, const std::vector<Light>& lights,
                                         const std::vector<AreaLight>& area_lights,
                                         int area_strata) {
  std::vector<glm::vec3> e(patches.size(), glm::vec3(0.0f));
  direct_irradiance(tracer, samples, patches, lights, area_lights, area_strata,
                    std::span<glm::vec3>(e));
  return e;
}

void direct_irradiance(const RayTracer& tracer, const SampleSet& samples, const PatchSet& patches,
                       const std::vector<Light>& lights, const std::vector<AreaLight>& area_lights,
                       int area_strata, std::span<glm::vec3> e, std::span<glm::vec3> sample_e) {
  // Frames only where a point or spot light will use them.
  const bool point_lights = has_point_or_spot_light(lights);
  const std::vector<CarriedPolygonFrame> frames =
      point_lights ? carried_polygon_frames(samples) : std::vector<CarriedPolygonFrame>{};
  direct_irradiance(tracer, samples, frames, patches, lights, area_lights, area_strata, e,
                    sample_e);
}

void direct_irradiance(const RayTracer& tracer, const SampleSet& samples,
                       std::span<const CarriedPolygonFrame> frames, const PatchSet& patches,
                       const std::vector<Light>& lights, const std::vector<AreaLight>& area_lights,
                       int area_strata, std::span<glm::vec3> e, std::span<glm::vec3> sample_e,
                       AreaLightCache* area_cache, ShadowBudget* shadows) {
  if (!sample_e.empty() && sample_e.size() != samples.samples.size())
    throw Error("direct light", "the per-sample output has " + std::to_string(sample_e.size()) +
                                    " entries for " + std::to_string(samples.samples.size()) +
                                    " samples");
  if (e.size() != patches.size())
    throw Error("direct light", "the output has " + std::to_string(e.size()) + " entries for " +
                                    std::to_string(patches.size()) + " patches");
  const float eps = 10.0f * tracer.epsilon();
  // Samples without their polygons (a bake folder that does not store them,
  // bake_reader.cpp): point and spot lights are then evaluated at the sample.
  const bool polygons = samples.carried_first.size() == samples.samples.size() + 1;
  const bool point_lights = has_point_or_spot_light(lights);
  if (polygons && point_lights && frames.size() != samples.carried.size())
    throw Error("direct light", "the polygon frames have " + std::to_string(frames.size()) +
                                    " entries for " + std::to_string(samples.carried.size()) +
                                    " carried polygons");
  // Each light's reach (and a spot's cone) once, not once per sample (a
  // spot's two cosines and the light's direction cost as much as the rest
  // of a sample's sun light).
  std::vector<LightReach> reach;
  for (const Light& light : lights) reach.emplace_back(light);
  // The samples' light from the area lights: the caller's kept one, or
  // worked out for this call alone.
  AreaLightCache this_call;
  const std::vector<glm::vec3>& area_e =
      (area_cache ? *area_cache : this_call)
          .irradiance(samples.samples.data(), samples.samples.size(), area_lights, area_strata,
                      [&](auto& out) {
                        area_irradiance_per_sample(tracer, samples, area_lights, area_strata, out);
                      });
  // Each light's kept visibility per sample, with a shadow budget whose
  // batches are the patches.
  std::vector<std::uint8_t*> kept(lights.size(), nullptr);
  if (shadows) {
    shadows->begin_frame(samples.samples.data(), patches.size(), lights);
    for (std::size_t li = 0; li < lights.size(); ++li)
      kept[li] = shadows->visibility_of(li, samples.samples.size()).data();
  }
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(patches.size()); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    glm::vec3 power(0.0f);
    float area = 0.0f;
    for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
      const std::uint32_t si = patches.member_samples[k];
      const Sample& s = samples.samples[si];
      glm::vec3 es(0.0f);             // irradiance at the sample, for what is evaluated there
      glm::vec3 polygon_power(0.0f);  // integrated over its polygons
      for (std::size_t li = 0; li < lights.size(); ++li) {
        const Light& light = lights[li];
        SampleShadow shadow(kept[li] ? kept[li] + si : nullptr, !shadows || shadows->traced(li, p));
        if (polygons && light.type != Light::Type::Directional)
          polygon_power +=
              point_light_power(tracer, samples, frames, si, light, reach[li].cone(), eps, shadow);
        else
          es += from_light(tracer, s.position, s.normal, reach[li], eps, shadow);
      }
      if (!area_e.empty()) es += area_e[si];
      power += polygon_power + s.area * es;
      if (!sample_e.empty()) sample_e[si] = s.area > 0.0f ? es + polygon_power / s.area : es;
      area += s.area;
    }
    e[p] = area > 0.0f ? power / area : glm::vec3(0.0f);
  }
}

LightReach::LightReach(const Light& light)
    : directional_(light.type == Light::Type::Directional),
      position_(light.position),
      power_(light.color * light.intensity),
      cone_(light) {
  if (directional_) to_light_ = -glm::normalize(light.direction);
}

glm::vec3 irradiance_at(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                        const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                        int area_strata, std::uint64_t seed) {
  const float eps = 10.0f * tracer.epsilon();  // the same offset as for patch samples
  glm::vec3 e(0.0f);
  for (const Light& light : lights) {
    SampleShadow shadow;
    e += from_light(tracer, p, n, LightReach(light), eps, shadow);
  }
  for (const AreaLight& light : area)
    e += area_light_irradiance(tracer, p, n, light, area_strata, seed);
  return e;
}

std::vector<glm::vec3> first_bounce(const PatchSet& patches,
                                    const std::vector<glm::vec3>& irradiance) {
  std::vector<glm::vec3> b(patches.size());
  for (std::size_t p = 0; p < patches.size(); ++p) b[p] = patches.patches[p].albedo * irradiance[p];
  return b;
}

std::vector<Light> evaluation_lights(const Scene& scene) {
  std::vector<Light> lights = scene.lights;
  const Bounds b = scene.bounds();
  const glm::vec3 c = b.center(), e = b.extent();
  int k = 0;
  for (float sx : {-0.2f, 0.2f})
    for (float sz : {-0.2f, 0.2f}) {
      Light l;
      l.type = Light::Type::Point;
      l.name = "evaluation-" + std::to_string(k++);
      l.position = c + e * glm::vec3(sx, 0.2f, sz);
      l.intensity = 1.0f;
      lights.push_back(l);
    }
  // Suns: a scene open to the sky is lit through its openings, by light that
  // lands on a few patches (a sunlit floor) and enters T through their
  // columns alone. A closed scene shadows them entirely; they then carry no
  // light and drop out of every error figure.
  const glm::vec3 up = glm::normalize(scene.camera.up);
  const glm::vec3 side = std::abs(up.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 east = glm::normalize(glm::cross(up, side)), north = glm::cross(east, up);
  k = 0;
  for (const auto& [elevation_deg, azimuth_deg] : kEvaluationSuns) {
    const float el = glm::radians(elevation_deg), az = glm::radians(azimuth_deg);
    const glm::vec3 to_sun =
        std::sin(el) * up + std::cos(el) * (std::cos(az) * east + std::sin(az) * north);
    Light l;
    l.type = Light::Type::Directional;
    l.name = "evaluation-sun-" + std::to_string(k++);
    l.direction = -to_sun;
    l.intensity = 1.0f;
    lights.push_back(l);
  }
  return lights;
}

}  // namespace bounce
