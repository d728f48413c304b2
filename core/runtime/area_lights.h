#pragma once
// Emissive triangles as area lights (scene.json materials with emission, the
// Cornell box's ceiling light): direct irradiance at a point, with soft
// shadows.
//
// Emission is exitance M (W/m^2, docs/scene-format.md), so the emitter's
// radiance is M / pi and the irradiance at p with normal n is
//   E = (M / pi) * integral over the triangle of V cos_p cos_l / r^2 dA,
// with V the visibility. An untextured emitter's integral without V is the
// form factor, known in closed form (point_to_polygon_form_factor in
// base/form_factor_kernel.h); only V is sampled, as the ratio of the
// integrand's jittered samples that reach the emitter (a ratio estimator:
// exact wherever the emitter is wholly seen or wholly hidden, noisy only in
// a penumbra). A textured emitter is sampled
// whole: g x g jittered strata, each weighed by its texel (stratified Monte
// Carlo, error falling as g^-3/2 for smooth integrands).
#include <array>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "raytrace/ray_tracer.h"
#include "scene/scene.h"

namespace bounce {

struct AreaLight {
  std::uint32_t triangle = 0;
  glm::vec3 v0{0.0f}, e1{0.0f}, e2{0.0f};  // corner and edges
  glm::vec3 normal{0.0f};                  // unit, the emitting side
  glm::vec3 exitance{0.0f};                // with an emissive texture, its mean over the material
  float area = 0.0f;
  bool two_sided = false;  // emits from both sides
  // A textured area light: the exitance at a point is emission_factor x the
  // emissive texture there (corner texture coordinates uv), so each stratum
  // sample weighs its own texel. Null: `exitance` everywhere.
  std::shared_ptr<const Texture> emission_texture;
  glm::vec3 emission_factor{0.0f};
  std::array<glm::vec2, 3> uv{};
};

// Shadow rays per point and emissive triangle: kAreaStrata x kAreaStrata.
// On the Cornell box's patches 3 x 3 rays with the closed-form form factor
// come as close to the light as 4 x 4 did with the whole emitter sampled
// (0.70% and 0.72% relative RMS against 24 x 24: test_area_light_patches).
inline constexpr int kAreaStrata = 3;

// Every emissive triangle of the scene.
std::vector<AreaLight> area_lights(const Scene& scene);

// Irradiance at p (unit normal n) from one area light, with shadow rays.
// `strata`: g, so g*g shadow rays; `seed` makes the jitter reproducible per
// point.
glm::vec3 area_light_irradiance(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                                const AreaLight& light, int strata, std::uint64_t seed);

// The same for `count` points at once, added to e[i]: point i (p[i], n[i])
// takes seed `first_seed + i`, so each gets what area_light_irradiance()
// gives it. Their shadow rays go to the tracer in batches (Embree's stream
// API), a third faster than one call per ray.
void add_area_light_irradiance(const RayTracer& tracer, const glm::vec3* p, const glm::vec3* n,
                               std::size_t count, const AreaLight& light, int strata,
                               std::uint64_t first_seed, glm::vec3* e);

// The irradiance from all of `area` at each point (p[i], n[i]) into out
// (sized here; empty when there are no area lights), on the threads in runs
// of points: point i takes seed i, `strata` squared rays per light, or one
// from point `one_ray_from` on.
void area_irradiance_at_points(const RayTracer& tracer, std::span<const glm::vec3> p,
                               std::span<const glm::vec3> n, const std::vector<AreaLight>& area,
                               int strata, std::size_t one_ray_from, std::vector<glm::vec3>& out);

}  // namespace bounce
