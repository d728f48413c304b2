#include "runtime/area_lights.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "base/form_factor_kernel.h"
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
  glm::vec3 e(0.0f);
  add_area_light_irradiance(tracer, &p, &n, 1, light, strata, seed, &e);
  return e;
}

namespace {

// A batch of points' shadow rays towards one area light, and what each ray
// carries: its stratum point's cos_p cos_l / r^2, and on a textured emitter
// also that times the texel there.
struct StratumRays {
  std::vector<ShadowRay> ray;
  std::vector<float> weight;
  std::vector<glm::vec3> texel_weight;
  std::vector<std::uint8_t> blocked;
  // Per point: its rays [first[i], first[i + 1]) and, untextured, its form
  // factor (0: the emitter is out of its sight, no rays).
  std::vector<std::uint32_t> first;
  std::vector<double> form_factor;

  void clear() {
    ray.clear();
    weight.clear();
    texel_weight.clear();
    first.assign(1, 0);
    form_factor.clear();
  }
  void add(const glm::vec3& origin, const glm::vec3& d, float w, const glm::vec3& texel) {
    // Stop short of the emitter, which would otherwise occlude itself.
    ray.push_back(ShadowRay{origin, d, 0.0f, 1.0f - 1e-3f});
    weight.push_back(w);
    texel_weight.push_back(w * texel);
  }
};

// Point (origin, n)'s g x g jittered stratum rays: a jittered point of each
// stratum of the unit square, folded onto the triangle (u + v > 1 mirrored),
// is uniform over its area. Strata whose point the receiver or the emitter
// faces away from take no ray.
void add_stratum_rays(const glm::vec3& origin, const glm::vec3& n, const AreaLight& light,
                      int strata, std::uint64_t seed, StratumRays& out) {
  Rng rng(seed, light.triangle);
  for (int i = 0; i < strata; ++i)
    for (int j = 0; j < strata; ++j) {
      float u = (static_cast<float>(i) + rng.uniform()) / static_cast<float>(strata);
      float v = (static_cast<float>(j) + rng.uniform()) / static_cast<float>(strata);
      if (u + v > 1.0f) {
        u = 1.0f - u;
        v = 1.0f - v;
      }
      const glm::vec3 d = light.v0 + u * light.e1 + v * light.e2 - origin;
      const float r2 = glm::dot(d, d);
      if (!(r2 > 0.0f)) continue;
      const glm::vec3 dir = d / std::sqrt(r2);
      const float cos_p = glm::dot(n, dir);
      float cos_l = -glm::dot(light.normal, dir);
      if (light.two_sided) cos_l = std::abs(cos_l);
      if (cos_p <= 0.0f || cos_l <= 0.0f) continue;
      const glm::vec3 texel =
          light.emission_texture
              ? light.emission_texture->lookup(light.uv[0] + u * (light.uv[1] - light.uv[0]) +
                                               v * (light.uv[2] - light.uv[0]))
              : glm::vec3(1.0f);
      out.add(origin, d, cos_p * cos_l / r2, texel);
    }
}

// The form factor from (origin, n) to the emitter, 0 from behind a
// one-sided one.
double emitter_form_factor(const glm::vec3& origin, const glm::vec3& n, const AreaLight& light,
                           const glm::vec3 (&corners)[3]) {
  const float side = glm::dot(light.normal, origin - light.v0);
  if (!(side > 0.0f) && !(light.two_sided && side < 0.0f)) return 0.0;
  return point_to_polygon_form_factor(origin, n, corners, 3);
}

// One point's rays: untextured, only where the emitter is in sight, and one
// ray to the mean of its corners above the receiver's horizon (a point of
// the part in sight) when no stratum point landed on that part (a sliver).
void add_point_rays(const glm::vec3& origin, const glm::vec3& n, const AreaLight& light, int strata,
                    std::uint64_t seed, StratumRays& out) {
  if (light.emission_texture) {
    add_stratum_rays(origin, n, light, strata, seed, out);
  } else {
    const glm::vec3 corners[3] = {light.v0, light.v0 + light.e1, light.v0 + light.e2};
    const double f = emitter_form_factor(origin, n, light, corners);
    out.form_factor.push_back(f);
    if (f > 0.0) {
      add_stratum_rays(origin, n, light, strata, seed, out);
      if (out.ray.size() == out.first.back()) {
        glm::vec3 above(0.0f);
        float count = 0.0f;
        for (const glm::vec3& c : corners)
          if (glm::dot(n, c - origin) > 0.0f) {
            above += c;
            count += 1.0f;
          }
        out.add(origin, above / count - origin, 1.0f, glm::vec3(1.0f));
      }
    }
  }
  out.first.push_back(static_cast<std::uint32_t>(out.ray.size()));
}

// Point k's irradiance from its traced rays.
glm::vec3 point_irradiance(const StratumRays& r, std::size_t k, const AreaLight& light,
                           int strata) {
  if (light.emission_texture) {
    glm::dvec3 sum(0.0);
    for (std::uint32_t i = r.first[k]; i < r.first[k + 1]; ++i)
      if (!r.blocked[i]) sum += glm::dvec3(r.texel_weight[i]);
    const double scale =
        static_cast<double>(light.area) / (static_cast<double>(strata) * strata * std::numbers::pi);
    return light.emission_factor * glm::vec3(sum * scale);
  }
  double all = 0.0, seen = 0.0;
  for (std::uint32_t i = r.first[k]; i < r.first[k + 1]; ++i) {
    all += r.weight[i];
    if (!r.blocked[i]) seen += r.weight[i];
  }
  if (!(all > 0.0)) return glm::vec3(0.0f);
  return light.exitance * static_cast<float>(r.form_factor[k] * seen / all);
}

}  // namespace

void add_area_light_irradiance(const RayTracer& tracer, const glm::vec3* p, const glm::vec3* n,
                               std::size_t count, const AreaLight& light, int strata,
                               std::uint64_t first_seed, glm::vec3* e) {
  const float eps = 10.0f * tracer.epsilon();
  // About a thousand rays per call to the tracer.
  const std::size_t per_batch =
      std::max<std::size_t>(1, 1024 / static_cast<std::size_t>(strata * strata));
  thread_local StratumRays rays;
  for (std::size_t lo = 0; lo < count; lo += per_batch) {
    const std::size_t hi = std::min(count, lo + per_batch);
    rays.clear();
    for (std::size_t i = lo; i < hi; ++i)
      add_point_rays(p[i] + eps * n[i], n[i], light, strata, first_seed + i, rays);
    rays.blocked.resize(rays.ray.size());
    tracer.occluded(rays.ray.data(), rays.ray.size(), rays.blocked.data());
    for (std::size_t i = lo; i < hi; ++i) e[i] += point_irradiance(rays, i - lo, light, strata);
  }
}

void area_irradiance_at_points(const RayTracer& tracer, std::span<const glm::vec3> p,
                               std::span<const glm::vec3> n, const std::vector<AreaLight>& area,
                               int strata, std::size_t one_ray_from, std::vector<glm::vec3>& out) {
  const std::size_t count = area.empty() ? 0 : p.size();
  out.assign(count, glm::vec3(0.0f));
  constexpr std::size_t kRun = 256;
#pragma omp parallel for schedule(dynamic, 1)
  for (std::int64_t r = 0; r < static_cast<std::int64_t>((count + kRun - 1) / kRun); ++r) {
    const std::size_t lo = static_cast<std::size_t>(r) * kRun, hi = std::min(count, lo + kRun);
    const std::size_t mid = std::clamp(one_ray_from, lo, hi);
    for (const AreaLight& light : area) {
      add_area_light_irradiance(tracer, &p[lo], &n[lo], mid - lo, light, strata, lo, &out[lo]);
      add_area_light_irradiance(tracer, p.data() + mid, n.data() + mid, hi - mid, light, 1, mid,
                                out.data() + mid);
    }
  }
}

}  // namespace bounce
