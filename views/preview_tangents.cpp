#include "preview_tangents.h"

#include <cmath>
#include <cstddef>
#include <cstdint>

namespace bounce::views {

namespace {

bool finite(const glm::vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }

// The part of t orthogonal to the unit normal n, made unit; zero when t is
// (nearly) along n or not finite.
glm::vec3 orthogonal_unit(const glm::dvec3& t, const glm::vec3& n) {
  const glm::dvec3 dn(n);
  const glm::dvec3 o = t - dn * glm::dot(dn, t);
  const double length = glm::length(o);
  if (!(length > 1e-12) || !std::isfinite(length)) return glm::vec3(0.0f);
  return glm::vec3(o / length);
}

}  // namespace

std::vector<glm::vec4> corner_tangents(const Scene& scene, const LitMesh& mesh) {
  const std::size_t faces = mesh.triangles.size();
  std::vector<glm::vec4> out(3 * faces, glm::vec4(0.0f));
  if (scene.triangle_uv.empty()) return out;
  // Per face its unit tangent and handedness (0: none); per vertex and
  // handedness the area-weighted sum of its faces' tangents.
  std::vector<glm::vec3> face_tangent(faces, glm::vec3(0.0f));
  std::vector<float> face_sign(faces, 0.0f);
  std::vector<glm::dvec3> sum(2 * mesh.positions.size(), glm::dvec3(0.0));
  const auto slot = [](std::uint32_t v, float sign) { return 2 * std::size_t{v} + (sign < 0.f); };
  for (std::size_t f = 0; f < faces; ++f) {
    const std::uint32_t source = mesh.source_triangle[f];
    bool mapped = true;
    for (const glm::vec2& uv : scene.triangle_uv[source]) mapped = mapped && finite(uv);
    if (!mapped) continue;
    const glm::uvec3& t = mesh.triangles[f];
    const glm::dvec3 p0(mesh.positions[t[0]]), p1(mesh.positions[t[1]]), p2(mesh.positions[t[2]]);
    const glm::dvec2 uv0(texture_coordinates(scene, source, mesh.positions[t[0]]));
    const glm::dvec2 d1 =
        glm::dvec2(texture_coordinates(scene, source, mesh.positions[t[1]])) - uv0;
    const glm::dvec2 d2 =
        glm::dvec2(texture_coordinates(scene, source, mesh.positions[t[2]])) - uv0;
    const glm::dvec3 e1 = p1 - p0, e2 = p2 - p0;
    const double det = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(det) > 0.0) || !std::isfinite(det)) continue;
    const glm::dvec3 tangent = (e1 * d2.y - e2 * d1.y) / det;
    const glm::dvec3 bitangent = (e2 * d1.x - e1 * d2.x) / det;
    const glm::dvec3 cross = glm::cross(e1, e2);
    const double length = glm::length(tangent);
    if (!(length > 0.0) || !std::isfinite(length)) continue;
    const float sign = glm::dot(glm::cross(cross, tangent), bitangent) < 0.0 ? -1.0f : 1.0f;
    face_tangent[f] = glm::vec3(tangent / length);
    face_sign[f] = sign;
    const double area = 0.5 * glm::length(cross);
    for (int c = 0; c < 3; ++c) sum[slot(t[c], sign)] += area * (tangent / length);
  }
  for (std::size_t f = 0; f < faces; ++f) {
    if (face_sign[f] == 0.0f) continue;
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t v = mesh.triangles[f][c];
      const glm::vec3& n = mesh.normals[v];
      glm::vec3 tangent = orthogonal_unit(sum[slot(v, face_sign[f])], n);
      // Opposite tangents of a vertex's faces can cancel: the face's own then.
      if (tangent == glm::vec3(0.0f)) tangent = orthogonal_unit(glm::dvec3(face_tangent[f]), n);
      if (tangent == glm::vec3(0.0f)) continue;
      out[3 * f + static_cast<std::size_t>(c)] = glm::vec4(tangent, face_sign[f]);
    }
  }
  return out;
}

}  // namespace bounce::views
