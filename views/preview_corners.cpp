#include "preview_corners.h"

#include <cmath>

#include "preview_tangents.h"

namespace bounce::views {

namespace {

// Whether the scene triangle has texture coordinates. A piece without them
// has NaN ones in the core, where lookups answer the texture's mean and a
// mask keeps the surface (a constant mask still applies): the shaders are
// told per corner, as OpenGL lookups at NaN are undefined.
bool has_texture_coordinates(const Scene& scene, std::uint32_t source) {
  if (scene.triangle_uv.empty()) return false;
  for (const glm::vec2& uv : scene.triangle_uv[source])
    if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return false;
  return true;
}

void add_face(const Scene& scene, const LitMesh& mesh, const std::vector<glm::vec4>& tangents,
              std::uint32_t f, PreviewCorners& out) {
  const std::uint32_t source = mesh.source_triangle[f];
  const Material& m = scene.materials[scene.triangle_material[source]];
  const bool mapped = has_texture_coordinates(scene, source);
  // Textured, the shader multiplies the texel by this factor (and clamps to
  // the core's albedo range, as Scene::albedo_at does); likewise the
  // emission factor of a textured emitter.
  const glm::vec3 albedo = mapped && m.texture ? m.texture_factor : m.albedo;
  const glm::vec3 emission = mapped && m.emission_texture ? m.emission_factor : m.emission;
  for (int c = 0; c < 3; ++c) {
    const std::uint32_t v = mesh.triangles[f][c];
    out.vertex.push_back(v);
    // The vertex colour multiplies the albedo (or the texture's factor).
    const glm::vec3 coloured = albedo * scene.colour_at(source, mesh.positions[v]);
    for (const glm::vec3& a : {mesh.positions[v], mesh.normals[v], coloured, emission})
      out.floats.insert(out.floats.end(), {a.x, a.y, a.z});
    const glm::vec2 uv =
        mapped ? texture_coordinates(scene, source, mesh.positions[v]) : glm::vec2(0.0f);
    out.floats.insert(out.floats.end(), {uv.x, uv.y, mapped ? 1.0f : 0.0f});
    const glm::vec4& t = tangents[3 * std::size_t{f} + static_cast<std::size_t>(c)];
    out.floats.insert(out.floats.end(), {t.x, t.y, t.z, t.w});
  }
}

}  // namespace

PreviewCorners preview_corners(const Scene& scene, const LitMesh& mesh) {
  std::vector<std::vector<std::uint32_t>> faces_of(scene.materials.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    faces_of[scene.triangle_material[mesh.source_triangle[f]]].push_back(
        static_cast<std::uint32_t>(f));
  const std::vector<glm::vec4> tangents = corner_tangents(scene, mesh);
  PreviewCorners out;
  out.floats.reserve(mesh.triangles.size() * 3 * PreviewCorners::kFloats);
  out.vertex.reserve(mesh.triangles.size() * 3);
  for (std::size_t material = 0; material < faces_of.size(); ++material) {
    if (faces_of[material].empty()) continue;
    PreviewCorners::MaterialRange range;
    range.first = out.vertex.size();
    range.material = material;
    for (const std::uint32_t f : faces_of[material]) add_face(scene, mesh, tangents, f, out);
    range.count = out.vertex.size() - range.first;
    out.materials.push_back(range);
  }
  return out;
}

}  // namespace bounce::views
