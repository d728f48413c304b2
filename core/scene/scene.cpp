#include "scene/scene.h"

#include <algorithm>
#include <array>

#include "scene/alpha_mask.h"
#include "scene/surface_texture.h"
#include "scene/texture.h"

namespace bounce {

namespace {

// Barycentric coordinates (s, t) of point p on (or projected onto the plane
// of) triangle tri, the point (1 - s - t) v0 + s v1 + t v2, in double: p may
// be far from the origin. The centroid's for a triangle without area.
glm::dvec2 barycentric(const Scene& scene, std::size_t tri, const glm::vec3& p) {
  const glm::dvec3 a(scene.vertex(tri, 0)), b(scene.vertex(tri, 1)), c(scene.vertex(tri, 2));
  const glm::dvec3 e1 = b - a, e2 = c - a, d = glm::dvec3(p) - a;
  const double d11 = glm::dot(e1, e1), d12 = glm::dot(e1, e2), d22 = glm::dot(e2, e2);
  const double den = d11 * d22 - d12 * d12;
  if (!(den > 0.0)) return glm::dvec2(1.0 / 3.0);
  const double p1 = glm::dot(d, e1), p2 = glm::dot(d, e2);
  return {(d22 * p1 - d12 * p2) / den, (d11 * p2 - d12 * p1) / den};
}

// Texture coordinates of point p on triangle tri.
glm::vec2 uv_at(const Scene& scene, std::size_t tri, const glm::vec3& p) {
  const auto& uv = scene.triangle_uv[tri];
  const glm::dvec2 st = barycentric(scene, tri, p);
  const glm::dvec2 r =
      glm::dvec2(uv[0]) + st.x * glm::dvec2(uv[1] - uv[0]) + st.y * glm::dvec2(uv[2] - uv[0]);
  return glm::vec2(r);
}

glm::vec3 textured_albedo(const Material& m, const glm::vec3& texel) {
  return glm::clamp(m.texture_factor * texel, glm::vec3(0.0f), glm::vec3(kMaxAlbedo));
}

// One triangle of a polygon's fan: its corners, their texture coordinates
// (zero when the scene has none) and its area.
struct FanTriangle {
  std::array<glm::vec3, 3> corner;
  std::array<glm::vec2, 3> uv;
  double area;
};

// Walks a planar polygon lying on triangle tri (count >= 3) as a fan of
// triangles from its first corner, calling f on each that has area; returns
// their total area (0: the polygon has none). Every mean over a polygon
// (albedo, emission, solid fraction) is this walk, each fan triangle
// weighted by its area.
template <class F>
double walk_fan(const Scene& scene, std::size_t tri, const glm::vec3* polygon, std::size_t count,
                F&& f) {
  const bool mapped = !scene.triangle_uv.empty();
  const auto uv = [&](const glm::vec3& p) { return mapped ? uv_at(scene, tri, p) : glm::vec2(0); };
  double total = 0.0;
  const glm::vec2 uv0 = uv(polygon[0]);
  glm::vec2 prev = uv(polygon[1]);
  for (std::size_t k = 2; k < count; ++k) {
    const glm::vec2 next = uv(polygon[k]);
    const double area = 0.5 * glm::length(glm::cross(glm::dvec3(polygon[k - 1] - polygon[0]),
                                                     glm::dvec3(polygon[k] - polygon[0])));
    if (area > 0.0) {
      f(FanTriangle{{polygon[0], polygon[k - 1], polygon[k]}, {uv0, prev, next}, area});
      total += area;
    }
    prev = next;
  }
  return total;
}

glm::vec3 centroid(const FanTriangle& f) {
  return (f.corner[0] + f.corner[1] + f.corner[2]) / 3.0f;
}

// The texel at uv, over the solid part when `solid` is given (the weighted
// texels about uv over their weight; the plain texel where none of them is
// solid).
glm::vec3 texel_at(const Texture& texture, const WeightedTexture* solid, glm::vec2 uv) {
  if (solid) {
    const WeightedTexture::Parts at = solid->lookup(uv);
    if (at.weight > 0.0) return glm::vec3(at.weighted / at.weight);
  }
  return texture.lookup(uv);
}

// The mean of `texture` over a planar polygon lying on triangle tri, each
// fan triangle's mean weighted by the vertex colour at its centroid when
// `coloured` (exact for a constant colour, and to second order in the
// triangle's size otherwise); the looked-up value at the first corner when
// the polygon has no area. With `solid` (a masked texture's solid part) the
// mean over the solid part: each fan triangle's weighted texels and weights
// from one lattice, summed over the fan before the division; the plain mean
// where the polygon holds no solid texel (a polygon the mask cuts away
// whole carries no area, but has a colour all the same).
glm::vec3 polygon_mean(const Scene& scene, std::size_t tri, const Texture& texture,
                       const WeightedTexture* solid, const glm::vec3* polygon, std::size_t count,
                       bool coloured) {
  const auto colour = [&](const FanTriangle& f) {
    return coloured ? glm::dvec3(scene.colour_at(tri, centroid(f))) : glm::dvec3(1.0);
  };
  if (solid) {
    glm::dvec3 sum(0.0);
    double weight = 0.0;
    walk_fan(scene, tri, polygon, count, [&](const FanTriangle& f) {
      const WeightedTexture::Parts mean = solid->mean_over_triangle(f.uv);
      sum += f.area * colour(f) * mean.weighted;
      weight += f.area * mean.weight;
    });
    if (weight > 0.0) return glm::vec3(sum / weight);
  }
  glm::dvec3 sum(0.0);
  const double total = walk_fan(scene, tri, polygon, count, [&](const FanTriangle& f) {
    sum += f.area * colour(f) * glm::dvec3(texture.mean_over_triangle(f.uv));
  });
  if (!(total > 0.0)) {
    const glm::vec3 at = texel_at(texture, solid, uv_at(scene, tri, polygon[0]));
    return coloured ? at * scene.colour_at(tri, polygon[0]) : at;
  }
  return glm::vec3(sum / total);
}

// The vertex colour's mean over a planar polygon lying on triangle tri: the
// colour is linear over the triangle, so each fan triangle's mean is the
// colour at its centroid.
glm::vec3 colour_mean(const Scene& scene, std::size_t tri, const glm::vec3* polygon,
                      std::size_t count) {
  glm::dvec3 sum(0.0);
  const double total = walk_fan(scene, tri, polygon, count, [&](const FanTriangle& f) {
    sum += f.area * glm::dvec3(scene.colour_at(tri, centroid(f)));
  });
  if (!(total > 0.0)) return scene.colour_at(tri, polygon[0]);
  return glm::vec3(sum / total);
}

}  // namespace

glm::vec2 texture_coordinates(const Scene& scene, std::size_t tri, const glm::vec3& p) {
  if (scene.triangle_uv.empty()) return glm::vec2(0.0f);
  return uv_at(scene, tri, p);
}

glm::vec3 Scene::colour_at(std::size_t tri, const glm::vec3& p) const {
  if (!has_vertex_colours()) return glm::vec3(1.0f);
  const auto& c = triangle_colour[tri];
  const glm::dvec2 st = barycentric(*this, tri, p);
  const glm::dvec3 r =
      (1.0 - st.x - st.y) * glm::dvec3(c[0]) + st.x * glm::dvec3(c[1]) + st.y * glm::dvec3(c[2]);
  // Outside the triangle (a point projected from a neighbour) the
  // interpolation extrapolates; a colour stays in [0, 1].
  return glm::clamp(glm::vec3(r), glm::vec3(0.0f), glm::vec3(1.0f));
}

glm::vec3 Scene::flat_albedo_at(std::size_t tri, const glm::vec3& p) const {
  const Material& m = material_of(tri);
  return has_vertex_colours() ? m.albedo * colour_at(tri, p) : m.albedo;
}

glm::vec3 Scene::albedo_at(std::size_t tri, const glm::vec3& p) const {
  const Material& m = material_of(tri);
  if (!textured(tri)) return flat_albedo_at(tri, p);
  const glm::vec3 a =
      textured_albedo(m, texel_at(*m.texture, m.solid_texture.get(), uv_at(*this, tri, p)));
  return has_vertex_colours() ? a * colour_at(tri, p) : a;
}

glm::vec3 Scene::mean_albedo(std::size_t tri, const glm::vec3* polygon, std::size_t count) const {
  const Material& m = material_of(tri);
  if (count < 3) return count > 0 ? flat_albedo_at(tri, polygon[0]) : m.albedo;
  const bool coloured = has_vertex_colours();
  if (textured(tri)) {
    // The factor (and the clamp) after the mean, as for a whole texture:
    // the vertex colour, at most 1, goes inside it.
    return textured_albedo(
        m, polygon_mean(*this, tri, *m.texture, m.solid_texture.get(), polygon, count, coloured));
  }
  return coloured ? m.albedo * colour_mean(*this, tri, polygon, count) : m.albedo;
}

glm::vec3 Scene::emission_at(std::size_t tri, const glm::vec3& p) const {
  const Material& m = material_of(tri);
  if (!emission_textured(tri)) return m.emission;
  return m.emission_factor * m.emission_texture->lookup(uv_at(*this, tri, p));
}

glm::vec3 Scene::mean_emission(std::size_t tri, const glm::vec3* polygon, std::size_t count) const {
  const Material& m = material_of(tri);
  if (!emission_textured(tri) || count < 3) return m.emission;
  return m.emission_factor *
         polygon_mean(*this, tri, *m.emission_texture, nullptr, polygon, count, false);
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
  double sum = 0.0;
  const double total = walk_fan(*this, tri, polygon, count, [&](const FanTriangle& f) {
    sum += f.area *
           static_cast<double>(m.alpha_mask->solid_fraction(f.uv, m.alpha_factor, m.alpha_cutoff));
  });
  if (!(total > 0.0))
    return m.alpha_mask->lookup(uv_at(*this, tri, polygon[0])) * m.alpha_factor >= m.alpha_cutoff
               ? 1.0f
               : 0.0f;
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

std::optional<Light::Type> light_type_from_name(const std::string& name) {
  for (const Light::Type t : {Light::Type::Point, Light::Type::Spot, Light::Type::Directional})
    if (name == light_type_name(t)) return t;
  return std::nullopt;
}

Bounds Scene::bounds() const {
  Bounds b;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) b.extend(positions[t[k]]);
  return b;
}

}  // namespace bounce
