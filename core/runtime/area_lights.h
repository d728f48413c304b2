#pragma once
// Emissive triangles as area lights (scene.json materials with emission, the
// Cornell box's ceiling light): direct irradiance at a point by stratified
// sampling of each triangle with one shadow ray per sample, which also gives
// soft shadows.
//
// Emission is exitance M (W/m^2, docs/scene-format.md), so the emitter's
// radiance is M / pi and the irradiance at p with normal n is
//   E = (M / pi) * integral over the triangle of cos_p cos_l / r^2 dA,
// estimated with g x g jittered strata of the triangle (stratified Monte
// Carlo: error falls as g^-3/2 for smooth integrands).
#include <array>
#include <cstdint>
#include <memory>
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

// Every emissive triangle of the scene.
std::vector<AreaLight> area_lights(const Scene& scene);

// Irradiance at p (unit normal n) from one area light, with shadow rays.
// `strata`: g, so g*g samples; `seed` makes the jitter reproducible per point.
glm::vec3 area_light_irradiance(const RayTracer& tracer, const glm::vec3& p, const glm::vec3& n,
                                const AreaLight& light, int strata, std::uint64_t seed);

}  // namespace bounce
