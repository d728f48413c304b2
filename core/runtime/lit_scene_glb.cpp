#include "runtime/lit_scene_glb.h"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "base/error.h"
#include "io/tone_map.h"
#include "runtime/glb_materials.h"
#include "scene/surface_texture.h"

namespace bounce {

namespace {

// The light without the albedo of material m, per channel. A vertex colour
// that multiplied the albedo stays in it: a viewer multiplies COLOR_0 by the
// texture and its factor, so the colour reaches the picture as it did the bake.
glm::vec3 light_without_albedo(const glm::vec3& radiosity, const Material& m) {
  glm::vec3 out(0.0f);
  for (glm::length_t c = 0; c < 3; ++c)
    if (m.albedo[c] > 0.0f) out[c] = std::max(radiosity[c] - m.emission[c], 0.0f) / m.albedo[c];
  return out;
}

// A primitive's vertex: a lit-mesh vertex with texture coordinates (bit
// for bit: seams are exact copies or different values).
struct CornerKey {
  std::uint32_t vertex, u, v;
  bool operator==(const CornerKey&) const = default;
};
struct CornerKeyHash {
  std::size_t operator()(const CornerKey& k) const {
    std::uint64_t h = k.vertex;
    h = h * 0x9E3779B97F4A7C15ull ^ k.u;
    h = h * 0x9E3779B97F4A7C15ull ^ k.v;
    return static_cast<std::size_t>(h ^ (h >> 29));
  }
};

// One primitive's vertices, numbered in order of first use.
class PrimitiveBuilder {
 public:
  PrimitiveBuilder(std::size_t material, bool with_uv) : with_uv_(with_uv) {
    out_.material = material;
  }
  std::uint32_t vertex(const LitMesh& mesh, std::uint32_t v, const glm::vec2& uv,
                       const glm::vec3& light) {
    const CornerKey key{v, with_uv_ ? std::bit_cast<std::uint32_t>(uv.x) : 0u,
                        with_uv_ ? std::bit_cast<std::uint32_t>(uv.y) : 0u};
    const auto [it, added] =
        index_.try_emplace(key, static_cast<std::uint32_t>(out_.positions.size()));
    if (added) {
      out_.positions.push_back(mesh.positions[v]);
      out_.normals.push_back(mesh.normals[v]);
      if (with_uv_) out_.uv.push_back(uv);
      out_.light.push_back(light);
      out_.radiance.push_back(mesh.radiosity[v]);
    }
    return it->second;
  }
  void triangle(const glm::uvec3& t) { out_.triangles.push_back(t); }
  bool empty() const { return out_.triangles.empty(); }
  GlbPrimitive take() { return std::move(out_); }

 private:
  bool with_uv_;
  GlbPrimitive out_;
  std::unordered_map<CornerKey, std::uint32_t, CornerKeyHash> index_;
};

}  // namespace

float write_lit_scene_glb(const std::filesystem::path& path, const Scene& scene,
                          const LitMesh& mesh, const std::string& name) {
  const std::string where = path.string();
  const std::size_t n = mesh.positions.size();
  if (mesh.normals.size() != n || mesh.radiosity.size() != n ||
      mesh.source_triangle.size() != mesh.triangles.size())
    throw Error(where, "glTF: the lit mesh's arrays differ in count");
  if (n == 0 || mesh.triangles.empty())
    throw Error(where, "glTF: the mesh has no vertices or no triangles to export");
  for (const std::uint32_t t : mesh.source_triangle)
    if (t >= scene.triangle_count())
      throw Error(where, "glTF: the lit mesh names a triangle the scene does not have");
  for (const glm::uvec3& t : mesh.triangles)
    for (int c = 0; c < 3; ++c)
      if (t[c] >= n) throw Error(where, "glTF: a triangle names a vertex out of range");

  std::vector<bool> used(scene.materials.size(), false);
  for (const std::uint32_t t : mesh.source_triangle) used[scene.triangle_material[t]] = true;
  GlbMaterials materials = glb_materials(scene, used);

  // One light value per lit vertex, by the material it was lit with.
  const std::vector<std::uint32_t> lit_by = vertex_source_triangles(mesh);
  std::vector<glm::vec3> vertex_light(n);
  for (std::size_t v = 0; v < n; ++v) {
    const std::uint32_t material = scene.triangle_material[lit_by[v]];
    vertex_light[v] = materials.textured[material]
                          ? light_without_albedo(mesh.radiosity[v], scene.materials[material])
                          : mesh.radiosity[v];
  }

  GlbModel model;
  model.name = name;
  model.exposure = ToneMap::exposure_for(vertex_light);
  model.colours =
      "COLOR_0 = clamp(light x exposure, 0, 1), linear, where light is the radiosity on "
      "untextured materials and the radiosity without the albedo (irradiance) on textured "
      "ones; _RADIANCE = radiosity, linear, exact";
  model.images = std::move(materials.images);
  model.materials = std::move(materials.materials);

  const bool plain = model.materials.size() == 1;
  if (plain) {
    // Nothing textured or masked: the lit mesh as it is, vertex for vertex.
    model.primitives.push_back(
        {0, mesh.positions, mesh.normals, {}, vertex_light, mesh.radiosity, mesh.triangles});
  } else {
    std::vector<PrimitiveBuilder> builders;
    for (std::size_t m = 0; m < model.materials.size(); ++m) builders.emplace_back(m, m != 0);
    for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
      const std::uint32_t tri = mesh.source_triangle[f];
      const std::uint32_t material = scene.triangle_material[tri];
      const std::size_t g = materials.of_scene_material[material];
      const bool textured = materials.textured[material];
      glm::uvec3 corners;
      for (int c = 0; c < 3; ++c) {
        const std::uint32_t v = mesh.triangles[f][c];
        // glTF's texture space has v down from the image's top row; the
        // scene's has v up from its bottom row.
        const glm::vec2 uv =
            g == 0 ? glm::vec2(0.0f) : texture_coordinates(scene, tri, mesh.positions[v]);
        const glm::vec3 light =
            textured ? light_without_albedo(mesh.radiosity[v], scene.materials[material])
                     : mesh.radiosity[v];
        corners[c] = builders[g].vertex(mesh, v, glm::vec2(uv.x, 1.0f - uv.y), light);
      }
      builders[g].triangle(corners);
    }
    for (PrimitiveBuilder& b : builders)
      if (!b.empty()) model.primitives.push_back(b.take());
  }
  write_glb(path, model);
  return model.exposure;
}

}  // namespace bounce
