#pragma once
// The scene as the bake sees it: one flat triangle soup (so the ray tracer,
// voxeliser and sampler share indices), with per-triangle material and mesh,
// plus lights, camera and the scene's own bake defaults.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

struct Texture;
struct WeightedTexture;
struct AlphaMask;

// Albedo 1 in a closed scene makes sum_h (rho F)^h diverge; keep it below.
// Balanced form factors close a room's rows to float rounding (~1e-7), and
// the multi-bounce sum amplifies a row error d into d / (1 - albedo) of the
// light: at 0.9999 that is ~0.1%, at 0.99999 ~1%. 1 itself never converges.
inline constexpr float kMaxAlbedo = 0.9999f;

struct Material {
  std::string name;
  // Diffuse reflectance per channel, in [0, kMaxAlbedo]. With a texture it is
  // the surface's mean (texture_factor x the texture's mean, over its solid
  // texels when masked), for whatever cannot look the texture up.
  glm::vec3 albedo{0.8f};
  // Textured: the albedo at a point is texture_factor x the texel there
  // (OBJ Kd x map_Kd, glTF baseColorFactor x baseColorTexture), clamped.
  std::shared_ptr<const Texture> texture;
  glm::vec3 texture_factor{1.0f};
  // Alpha-masked (a cut-out: leaves, fences, grilles): where alpha_mask x
  // alpha_factor is below alpha_cutoff the surface is not there. Rays pass
  // through it and no sample or patch stands on it (OBJ map_d, glTF
  // alphaMode MASK). Null: the surface is whole.
  std::shared_ptr<const AlphaMask> alpha_mask;
  float alpha_factor = 1.0f;
  float alpha_cutoff = 0.5f;
  // Textured and masked: the texture over its solid part (solid_part in
  // scene/alpha_mask.h), which albedo, albedo_at and mean_albedo average
  // instead, so that the colour in the holes counts nowhere. Null
  // otherwise (also for a constant mask: the surface is whole or gone).
  std::shared_ptr<const WeightedTexture> solid_texture;
  // Emitted radiosity (W/m^2 per channel); > 0 makes an area light. With an
  // emissive texture it is the surface's mean (emission_factor x the
  // texture's mean), for whatever cannot look the texture up.
  glm::vec3 emission{0.0f};
  // Textured emission: the exitance at a point is emission_factor x the
  // texel there (OBJ Ke x map_Ke, glTF emissiveFactor x emissiveTexture), so
  // the surface is a textured area light. Null: emission everywhere.
  std::shared_ptr<const Texture> emission_texture;
  glm::vec3 emission_factor{0.0f};
  // Tangent-space normal map (OBJ norm, or map_bump / bump holding an RGB
  // image; glTF normalTexture), texels as stored (not decoded from sRGB):
  // the direction 2 c - 1 in the frame (tangent along +u, bitangent along
  // +v, the surface normal), its first two components times normal_scale
  // (glTF normalTexture.scale, OBJ -bm). Drawn by the studio's preview only:
  // the bake and the reference light the surface's geometric normal, see
  // docs/scene-format.md.
  std::shared_ptr<const Texture> normal_map;
  float normal_scale = 1.0f;
  bool is_emissive() const { return emission.r > 0.f || emission.g > 0.f || emission.b > 0.f; }
};

// The largest patch density a mesh may have (scene.json's
// meshes[i].patch_density, the studio's mesh list): a mesh at 64 times the
// others' density already takes nearly a whole budget from a scene of a few
// dozen equal meshes; more is a typo.
inline constexpr int kMaxPatchDensity = 64;

struct MeshInfo {
  std::string name;    // from scene.json or the file's node/mesh name
  std::string source;  // file it came from
  std::uint32_t first_triangle = 0;
  std::uint32_t triangle_count = 0;
  // Both sides of each triangle receive and emit light (thin walls, leaves);
  // otherwise only the side its winding faces (counter-clockwise = front).
  bool two_sided = false;
  // How many patches this mesh's surface gets relative to the rest: under a
  // total patch budget its voxels keep this many times the patches they
  // would otherwise, the others fewer, so the total stays the budget.
  float patch_density = 1.0f;
};

struct Light {
  enum class Type { Point, Spot, Directional };
  Type type = Type::Point;
  std::string name;
  glm::vec3 position{0.0f};
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // spot and directional: where the light goes
  glm::vec3 color{1.0f};
  float intensity = 1.0f;        // point/spot: W/sr per unit colour; directional: W/m^2
  float spot_inner_deg = 30.0f;  // full intensity inside this half-angle
  float spot_outer_deg = 45.0f;  // zero beyond this half-angle
};

// "point", "spot" or "directional", as scene.json spells them.
const char* light_type_name(Light::Type type);
// The type a name of light_type_name() stands for; nullopt for any other.
std::optional<Light::Type> light_type_from_name(const std::string& name);

struct Camera {
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float fov_y_deg = 45.0f;
};

// Settings a scene may suggest; the command line overrides each of them.
struct BakeDefaults {
  std::optional<int> voxel_resolution;  // cells along the longest axis
  std::optional<int> patches_total;     // target patch count (derives the resolution)
  std::optional<int> patches_per_voxel;
  std::optional<int> samples_per_face;
  // Relative RMS error of the indirect light the compressed matrix may cause
  // (BakeSettings::error_budget).
  std::optional<double> error_budget;
  // Which light probes to place, by the setting's choice name ("on",
  // "volumes", "off"), and the probe volumes as the setting's text
  // (runtime/probe_volume.h; empty: none).
  std::optional<std::string> light_probes;
  std::string light_probe_volumes;
};

struct Bounds {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{std::numeric_limits<float>::lowest()};
  void extend(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return lo.x > hi.x; }
  glm::vec3 extent() const { return empty() ? glm::vec3(0.0f) : hi - lo; }
  glm::vec3 center() const { return 0.5f * (lo + hi); }
};

struct Scene {
  std::string name;  // folder name for scene.json, file stem for a bare mesh
  std::string path;  // where it was loaded from

  std::vector<glm::vec3> positions;
  std::vector<glm::uvec3> triangles;
  std::vector<std::uint32_t> triangle_material;  // index into materials
  std::vector<std::uint32_t> triangle_mesh;      // index into meshes
  // Texture coordinates of each triangle's corners; empty when no material
  // has a texture, mask or normal map (then every albedo is its material's).
  std::vector<std::array<glm::vec2, 3>> triangle_uv;
  // Linear colour of each triangle's corners (the mesh files' per-vertex
  // colours, in [0, 1]): the albedo anywhere on a triangle is its material's
  // (texture x factor, or flat colour) times the colour interpolated there.
  // White for corners of meshes without colours; empty when no mesh has any.
  std::vector<std::array<glm::vec3, 3>> triangle_colour;
  std::vector<Material> materials;
  std::vector<MeshInfo> meshes;
  std::vector<Light> lights;
  Camera camera;
  BakeDefaults defaults;

  std::size_t triangle_count() const { return triangles.size(); }
  glm::vec3 vertex(std::size_t tri, int corner) const { return positions[triangles[tri][corner]]; }
  // Unnormalised geometric normal (cross product of edges): length = 2 * area.
  glm::vec3 triangle_cross(std::size_t tri) const;
  float triangle_area(std::size_t tri) const;
  const Material& material_of(std::size_t tri) const { return materials[triangle_material[tri]]; }
  bool two_sided(std::size_t tri) const { return meshes[triangle_mesh[tri]].two_sided; }
  bool textured(std::size_t tri) const {
    return !triangle_uv.empty() && material_of(tri).texture != nullptr;
  }
  // Whether triangle tri has holes cut by an alpha mask.
  bool masked(std::size_t tri) const {
    return !triangle_uv.empty() && material_of(tri).alpha_mask != nullptr;
  }
  bool has_masks() const;
  // Whether the surface is there at barycentric coordinates (b1, b2) of
  // triangle tri, the point (1 - b1 - b2) v0 + b1 v1 + b2 v2 (as a ray
  // tracer reports a hit).
  bool solid_at(std::size_t tri, float b1, float b2) const;
  // The fraction of a planar polygon lying on triangle tri where the
  // surface is there (1 for an unmasked triangle).
  float solid_fraction(std::size_t tri, const glm::vec3* polygon, std::size_t count) const;
  // Whether any mesh has per-vertex colours (then every albedo lookup
  // multiplies them in).
  bool has_vertex_colours() const { return !triangle_colour.empty(); }
  // The per-vertex colour interpolated at point p on (or projected onto the
  // plane of) triangle tri; white without vertex colours.
  glm::vec3 colour_at(std::size_t tri, const glm::vec3& p) const;
  // Albedo at point p on triangle tri (the texel there when textured, times
  // the vertex colour there).
  glm::vec3 albedo_at(std::size_t tri, const glm::vec3& p) const;
  // Mean albedo over a planar polygon lying on triangle tri.
  glm::vec3 mean_albedo(std::size_t tri, const glm::vec3* polygon, std::size_t count) const;
  // Albedo at point p on triangle tri for a renderer that does its own
  // texture lookups (or draws textures as their mean): the material's flat
  // albedo times the vertex colour there.
  glm::vec3 flat_albedo_at(std::size_t tri, const glm::vec3& p) const;
  // Whether triangle tri's emission follows an emissive texture.
  bool emission_textured(std::size_t tri) const {
    return !triangle_uv.empty() && material_of(tri).emission_texture != nullptr;
  }
  // Emission at point p on triangle tri (the texel there when textured).
  glm::vec3 emission_at(std::size_t tri, const glm::vec3& p) const;
  // Mean emission over a planar polygon lying on triangle tri.
  glm::vec3 mean_emission(std::size_t tri, const glm::vec3* polygon, std::size_t count) const;
  Bounds bounds() const;
};

}  // namespace bounce
