#pragma once
// Small analytic scenes built in memory, for tests that must not depend on
// the scene loader. The same shapes ship as files in resources/scenes/.
#include <numbers>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace bounce::test_scenes {

// Adds a mesh made of the given quads (counter-clockwise = front) or triangles.
inline void add_mesh(Scene& s, const std::string& name, const std::vector<glm::vec3>& vertices,
                     const std::vector<glm::uvec3>& triangles, glm::vec3 albedo = glm::vec3(0.5f),
                     glm::vec3 emission = glm::vec3(0.0f), bool two_sided = false) {
  const auto base = static_cast<std::uint32_t>(s.positions.size());
  const auto mesh = static_cast<std::uint32_t>(s.meshes.size());
  Material material;
  material.name = name;
  material.albedo = albedo;
  material.emission = emission;
  s.materials.push_back(material);
  s.meshes.push_back({name, "memory", static_cast<std::uint32_t>(s.triangles.size()),
                      static_cast<std::uint32_t>(triangles.size()), two_sided, 1.0f});
  s.positions.insert(s.positions.end(), vertices.begin(), vertices.end());
  for (const auto& t : triangles) {
    s.triangles.push_back(t + glm::uvec3(base));
    s.triangle_material.push_back(mesh);
    s.triangle_mesh.push_back(mesh);
  }
}

inline void add_quad(Scene& s, const std::string& name, glm::vec3 a, glm::vec3 b, glm::vec3 c,
                     glm::vec3 d, glm::vec3 albedo = glm::vec3(0.5f),
                     glm::vec3 emission = glm::vec3(0.0f)) {
  add_mesh(s, name, {a, b, c, d}, {{0, 1, 2}, {0, 2, 3}}, albedo, emission);
}

// Unit squares at z = 0 (facing +z) and z = 1 (facing -z).
inline Scene parallel_squares() {
  Scene s;
  s.name = "parallel-squares";
  add_quad(s, "bottom", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  add_quad(s, "top", {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
  return s;
}

// Floor y = 0 (facing +y) and wall z = 0 (facing +z) sharing the x edge.
inline Scene perpendicular_squares() {
  Scene s;
  s.name = "perpendicular-squares";
  add_quad(s, "floor", {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
  add_quad(s, "wall", {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  return s;
}

inline std::vector<glm::uvec3> fan(std::uint32_t segments) {
  std::vector<glm::uvec3> t;
  for (std::uint32_t k = 0; k < segments; ++k) t.push_back({0, 1 + k, 1 + (k + 1) % segments});
  return t;
}

inline std::vector<glm::vec3> disk(float radius, float z, bool facing_up, std::uint32_t segments) {
  std::vector<glm::vec3> v{{0, 0, z}};
  for (std::uint32_t k = 0; k < segments; ++k) {
    const float a = 2.0f * std::numbers::pi_v<float> * static_cast<float>(k) /
                    static_cast<float>(segments) * (facing_up ? 1.0f : -1.0f);
    v.push_back({radius * std::cos(a), radius * std::sin(a), z});
  }
  return v;
}

// Disk r = 0.1 at z = 0 facing +z; disk r = 0.2 at z = 0.5 facing -z.
inline Scene coaxial_disks() {
  Scene s;
  s.name = "coaxial-disks";
  add_mesh(s, "small", disk(0.1f, 0.0f, true, 128), fan(128));
  add_mesh(s, "large", disk(0.2f, 0.5f, false, 128), fan(128));
  return s;
}

// Closed unit cube, every face facing inward, uniform albedo and emission.
inline Scene furnace_box(glm::vec3 albedo = glm::vec3(0.5f), glm::vec3 emission = glm::vec3(1.0f)) {
  Scene s;
  s.name = "furnace";
  const glm::vec3 p[8] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                          {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  std::vector<glm::vec3> v(p, p + 8);
  // Inward-facing quads (counter-clockwise seen from inside).
  const std::vector<glm::uvec3> t = {{0, 1, 2}, {0, 2, 3}, {4, 7, 6}, {4, 6, 5},
                                     {0, 4, 5}, {0, 5, 1}, {3, 2, 6}, {3, 6, 7},
                                     {0, 3, 7}, {0, 7, 4}, {1, 5, 6}, {1, 6, 2}};
  add_mesh(s, "box", v, t, albedo, emission);
  return s;
}

}  // namespace bounce::test_scenes
