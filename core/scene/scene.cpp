#include "scene/scene.h"

#include <algorithm>

#include "scene/alpha_mask.h"
#include "scene/surface_texture.h"
#include "scene/texture.h"

namespace bounce {

namespace {

// Texture coordinates of point p on triangle tri, from its barycentric
// coordinates (in double: p may be far from the origin).
glm::vec2 uv_at(const Scene& scene, std::size_t tri, const glm::vec3& p) {
  const glm::dvec3 a(scene.vertex(tri, 0)), b(scene.vertex(tri, 1)), c(scene.vertex(tri, 2));
  const glm::dvec3 e1 = b - a, e2 = c - a, d = glm::dvec3(p) - a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double den = d11 * d22 - d12 * d12;
  const auto& uv = scene.triangle_uv[tri];
  if (!(den > 0.0)) return (uv[0] + uv[1] + uv[2]) / 3.0f;
  const double p1 = glm::dot(d, e1), p2 = glm::dot(d, e2);
  const double s = (d22 * p1 - d12 * p2) / den, t = (d11 * p2 - d12 * p1) / den;
  const glm::dvec2 r =
      glm::dvec2(uv[0]) + s * glm::dvec2(uv[1] - uv[0]) + t * glm::dvec2(uv[2] - uv[0]);
  return glm::vec2(r);
}

glm::vec3 textured_albedo(const Material& m, const glm::vec3& texel) {
  return glm::clamp(m.texture_factor * texel, glm::vec3(0.0f), glm::vec3(kMaxAlbedo));
}

// The mean of `texture` over a planar polygon lying on triangle tri: a fan
// of triangles, each weighted by its area (the texel at the first corner
// when the polygon has no area).
glm::vec3 polygon_mean(const Scene& scene, std::size_t tri, const Texture& texture,
                       const glm::vec3* polygon, std::size_t count) {
  glm::dvec3 sum(0.0);
  double total = 0.0;
  const glm::vec2 uv0 = uv_at(scene, tri, polygon[0]);
  glm::vec2 prev = uv_at(scene, tri, polygon[1]);
  for (std::size_t k = 2; k < count; ++k) {
    const glm::vec2 next = uv_at(scene, tri, polygon[k]);
    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(polygon[k - 1] - polygon[0]),
                                                     glm::dvec3(polygon[k] - polygon[0])));
    if (area > 0.0) {
      sum += area * glm::dvec3(texture.mean_over_triangle({uv0, prev, next}));
      total += area;
    }
    prev = next;
  }
  if (!(total > 0.0)) return texture.lookup(uv0);
  return glm::vec3(sum / total);
}

}  // namespace

glm::vec2 texture_coordinates(const Scene& scene, std::size_t tri, const glm::vec3& p) {
  if (scene.triangle_uv.empty()) return glm::vec2(0.0f);
  return uv_at(scene, tri, p);
}

glm::vec3 Scene::albedo_at(std::size_t tri, const glm::vec3& p) const {
  const Material& m = material_of(tri);
  if (!textured(tri)) return m.albedo;
  return textured_albedo(m, m.texture->lookup(uv_at(*this, tri, p)));
}

glm::vec3 Scene::mean_albedo(std::size_t tri, const glm::vec3* polygon, std::size_t count) const {
  const Material& m = material_of(tri);
  if (!textured(tri) || count < 3) return m.albedo;
  return textured_albedo(m, polygon_mean(*this, tri, *m.texture, polygon, count));
}

glm::vec3 Scene::emission_at(std::size_t tri, const glm::vec3& p) const {
  const Material& m = material_of(tri);
  if (!emission_textured(tri)) return m.emission;
  return m.emission_factor * m.emission_texture->lookup(uv_at(*this, tri, p));
}

glm::vec3 Scene::mean_emission(std::size_t tri, const glm::vec3* polygon, std::size_t count) const {
  const Material& m = material_of(tri);
  if (!emission_textured(tri) || count < 3) return m.emission;
  return m.emission_factor * polygon_mean(*this, tri, *m.emission_texture, polygon, count);
}

bool Scene::has_masks() const {
  if (triangle_uv.empty()) return false;
  return std::any_of(materials.begin(), materials.end(),
                     [](const Material& m) { return m.alpha_mask != nullptr; });
}

bool Scene::solid_at(std::size_t tri, float b1, float b2) const {
  if (!masked(tri)) return true;
  const Material& m = material_of(tri);
  const auto& uv = triangle_uv[tri];
  const glm::vec2 at = uv[0] + b1 * (uv[1] - uv[0]) + b2 * (uv[2] - uv[0]);
  return m.alpha_mask->lookup(at) * m.alpha_factor >= m.alpha_cutoff;
}

float Scene::solid_fraction(std::size_t tri, const glm::vec3* polygon, std::size_t count) const {
  if (!masked(tri)) return 1.0f;
  const Material& m = material_of(tri);
  if (count < 3)
    return count > 0 && m.alpha_mask->lookup(uv_at(*this, tri, polygon[0])) * m.alpha_factor >=
                            m.alpha_cutoff
               ? 1.0f
               : 0.0f;
  // Fan of triangles, each weighted by its area, as mean_albedo.
  double sum = 0.0, total = 0.0;
  const glm::vec2 uv0 = uv_at(*this, tri, polygon[0]);
  glm::vec2 prev = uv_at(*this, tri, polygon[1]);
  for (std::size_t k = 2; k < count; ++k) {
    const glm::vec2 next = uv_at(*this, tri, polygon[k]);
    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(polygon[k - 1] - polygon[0]),
                                                     glm::dvec3(polygon[k] - polygon[0])));
    if (area > 0.0) {
      sum += area * static_cast<double>(m.alpha_mask->solid_fraction(
                        {uv0, prev, next}, m.alpha_factor, m.alpha_cutoff));
      total += area;
    }
    prev = next;
  }
  if (!(total > 0.0))
    return m.alpha_mask->lookup(uv0) * m.alpha_factor >= m.alpha_cutoff ? 1.0f : 0.0f;
  return static_cast<float>(sum / total);
}

glm::vec3 Scene::triangle_cross(std::size_t tri) const {
  const glm::vec3 a = vertex(tri, 0), b = vertex(tri, 1), c = vertex(tri, 2);
  return glm::cross(b - a, c - a);
}

float Scene::triangle_area(std::size_t tri) const {
  return 0.5f * glm::length(triangle_cross(tri));
}

const char* light_type_name(Light::Type type) {
  switch (type) {
    case Light::Type::Point:
      return "point";
    case Light::Type::Spot:
      return "spot";
    case Light::Type::Directional:
      return "directional";
  }
  return "unknown";
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) b.extend(positions[t[k]]);
  return b;
}

}  // namespace bounce
