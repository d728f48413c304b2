#include "runtime/direct_light.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

// Irradiance at point p (normal n) from one light, visibility included.
glm::vec3 from_light(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                     const Light& light, float eps) {
  const glm::vec3 origin = p + eps * n;
  if (light.type == Light::Type::Directional) {
    const glm::vec3 to_light = -glm::normalize(light.direction);
    const float cos_n = glm::dot(n, to_light);
    if (cos_n <= 0.0f) return glm::vec3(0.0f);
    if (tracer.occluded(origin, to_light, 0.0f, std::numeric_limits<float>::infinity()))
      return glm::vec3(0.0f);
    return light.color * light.intensity * cos_n;
  }
  const glm::vec3 d = light.position - origin;
  const float r2 = glm::dot(d, d);
  if (!(r2 > 0.0f)) return glm::vec3(0.0f);
  const glm::vec3 dir = d / std::sqrt(r2);
  const float cos_n = glm::dot(n, dir);
  if (cos_n <= 0.0f) return glm::vec3(0.0f);
  float spot = 1.0f;
  if (light.type == Light::Type::Spot) {
    const float c = glm::dot(-dir, glm::normalize(light.direction));
    const float inner = std::cos(glm::radians(light.spot_inner_deg));
    const float outer = std::cos(glm::radians(light.spot_outer_deg));
    const float t = std::clamp((c - outer) / std::max(1e-6f, inner - outer), 0.0f, 1.0f);
    spot = t * t * (3.0f - 2.0f * t);  // smoothstep between the cones
    if (spot <= 0.0f) return glm::vec3(0.0f);
  }
  if (tracer.occluded(origin, d, 0.0f, 1.0f - 1e-4f)) return glm::vec3(0.0f);
  return light.color * light.intensity * spot * cos_n / r2;
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
                       int area_strata, std::span<glm::vec3> e) {
  if (e.size() != patches.size())
    throw Error("direct light", "the output has " + std::to_string(e.size()) + " entries for " +
                                    std::to_string(patches.size()) + " patches");
  const float eps = 10.0f * tracer.epsilon();
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t pi = 0; pi < static_cast<std::int64_t>(patches.size()); ++pi) {
    const auto p = static_cast<std::size_t>(pi);
    glm::vec3 sum(0.0f);
    float area = 0.0f;
    for (std::uint32_t k = patches.member_first[p]; k < patches.member_first[p + 1]; ++k) {
      const Sample& s = samples.samples[patches.member_samples[k]];
      glm::vec3 es(0.0f);
      for (const Light& light : lights) es += from_light(tracer, s.position, s.normal, light, eps);
      for (const AreaLight& light : area_lights)
        es += area_light_irradiance(tracer, s.position, s.normal, light, area_strata,
                                    patches.member_samples[k]);
      sum += s.area * es;
      area += s.area;
    }
    e[p] = area > 0.0f ? sum / area : glm::vec3(0.0f);
  }
}

glm::vec3 irradiance_at(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                        const std::vector<Light>& lights, const std::vector<AreaLight>& area,
                        int area_strata, std::uint64_t seed) {
  const float eps = 10.0f * tracer.epsilon();  // the same offset as for patch samples
  glm::vec3 e(0.0f);
  for (const Light& light : lights) e += from_light(tracer, p, n, light, eps);
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
  return lights;
}

}  // namespace bounce
