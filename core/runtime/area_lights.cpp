#include "runtime/area_lights.h"

#include <cmath>
#include <numbers>

#include "base/random.h"
#include "scene/texture.h"

namespace bounce {

std::vector<AreaLight> area_lights(const Scene& scene) {
  std::vector<AreaLight> lights;
  for (std::size_t t = 0; t < scene.triangle_count(); ++t) {
    const Material& m = scene.material_of(t);
    if (!m.is_emissive()) continue;
    AreaLight l;
    l.triangle = static_cast<std::uint32_t>(t);
    l.v0 = scene.vertex(t, 0);
    l.e1 = scene.vertex(t, 1) - l.v0;
    l.e2 = scene.vertex(t, 2) - l.v0;
    const glm::vec3 c = glm::cross(l.e1, l.e2);
    const float len = glm::length(c);
    if (!(len > 0.0f)) continue;  // the loader drops degenerate triangles; be safe
    l.normal = c / len;
    l.area = 0.5f * len;
    l.exitance = m.emission;
    l.two_sided = scene.two_sided(t);
    if (scene.emission_textured(t)) {
      l.emission_texture = m.emission_texture;
      l.emission_factor = m.emission_factor;
      l.uv = scene.triangle_uv[t];
    }
    lights.push_back(l);
  }
  return lights;
}

glm::vec3 area_light_irradiance(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                                const AreaLight& light, int strata, std::uint64_t seed) {
  Rng rng(seed, light.triangle);
  const float eps = 10.0f * tracer.epsilon();
  const glm::vec3 origin = p + eps * n;
  double sum = 0.0;
  glm::dvec3 textured_sum(0.0);  // the same, each sample times its texel
  for (int i = 0; i < strata; ++i)
    for (int j = 0; j < strata; ++j) {
      // A jittered point of the unit square, folded onto the triangle
      // (u + v > 1 mirrored): uniform over its area.
      float u = (static_cast<float>(i) + rng.uniform()) / static_cast<float>(strata);
      float v = (static_cast<float>(j) + rng.uniform()) / static_cast<float>(strata);
      if (u + v > 1.0f) {
        u = 1.0f - u;
        v = 1.0f - v;
      }
      const glm::vec3 q = light.v0 + u * light.e1 + v * light.e2;
      const glm::vec3 d = q - origin;
      const float r2 = glm::dot(d, d);
      if (!(r2 > 0.0f)) continue;
      const glm::vec3 dir = d / std::sqrt(r2);
      const float cos_p = glm::dot(n, dir);
      float cos_l = -glm::dot(light.normal, dir);
      if (light.two_sided) cos_l = std::abs(cos_l);
      if (cos_p <= 0.0f || cos_l <= 0.0f) continue;
      // Stop short of the emitter, which would otherwise occlude itself.
      if (tracer.occluded(origin, d, 0.0f, 1.0f - 1e-3f)) continue;
      const auto weight = static_cast<double>(cos_p * cos_l / r2);
      sum += weight;
      if (light.emission_texture)
        textured_sum +=
            weight *
            glm::dvec3(light.emission_texture->lookup(
                light.uv[0] + u * (light.uv[1] - light.uv[0]) + v * (light.uv[2] - light.uv[0])));
    }
  const double scale =
      static_cast<double>(light.area) / (static_cast<double>(strata) * strata * std::numbers::pi);
  if (light.emission_texture) return light.emission_factor * glm::vec3(textured_sum * scale);
  const double estimate =
      sum * static_cast<double>(light.area) / (static_cast<double>(strata) * strata);
  return light.exitance * static_cast<float>(estimate / std::numbers::pi);
}

}  // namespace bounce
