#pragma once
// One mesh file through Assimp: every (node, mesh) pair becomes a piece with
// its vertices moved into scene space (node transforms, then the scene.json
// transform), its triangles (winding kept front-facing under mirroring) and
// its material's stated diffuse and emissive colours as exact floats (and
// colour, emissive and normal textures, found but not yet read: files, or
// images embedded in the file, e.g. a .glb's), texture
// coordinates and per-vertex colours.
// Degenerate triangles are kept here; the scene builder counts and skips
// them once the scene's size is known. Internal to the scene module.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "base/diagnostics.h"
#include "scene/alpha_mask.h"
#include "scene/image_source.h"

namespace bounce::scene_internal {

struct ImportedMaterial {
  std::string name;
  std::optional<glm::vec3> albedo;  // nullopt when the file does not state one
  glm::vec3 emission{0.0f};
  // The colour texture as the file names it ("*0" for an embedded one), and
  // where it was found (nullopt: missing, already warned about; the albedo
  // falls back).
  std::string texture_name;
  std::optional<ImageSource> texture;
  // Alpha-masked: OBJ map_d (its own file, alpha or grey) or glTF alphaMode
  // MASK (the base colour texture's alpha; without a texture the mask is
  // the constant alpha_factor). mask is where the image was found (nullopt:
  // none, or missing and already warned about: the surface stays whole).
  bool masked = false;
  std::optional<ImageSource> mask;
  AlphaSource mask_source = AlphaSource::AlphaOrGrey;
  float alpha_factor = 1.0f;  // glTF baseColorFactor's alpha
  float alpha_cutoff = 0.5f;
  // The emissive texture (OBJ map_Ke, glTF emissiveTexture), where it was
  // found (nullopt: none, or missing and already warned about); `emission`
  // above is its factor.
  std::optional<ImageSource> emission_texture;
  // The tangent-space normal map (OBJ norm, or map_bump / bump; glTF
  // normalTexture), where it was found, and its scale (glTF
  // normalTexture.scale, OBJ -bm). An OBJ bump map may be a grey height map
  // instead: the builder reads the image and tells.
  std::optional<ImageSource> normal_map;
  float normal_scale = 1.0f;
};

struct ImportedPiece {
  std::string name;
  std::uint32_t material = 0;        // index into ImportedFile::materials
  std::vector<glm::vec3> positions;  // scene space; all finite where referenced
  std::vector<glm::uvec3> triangles;
  std::vector<glm::vec2> uvs;  // per position (first UV channel); empty when the file has none
  // Per position: the first set of vertex colours, linear, in [0, 1] (see
  // import_mesh_file); empty when the mesh has none.
  std::vector<glm::vec3> colours;
  std::size_t non_triangles = 0;  // point and line primitives, which have no area
};

struct ImportedFile {
  std::filesystem::path path;
  std::vector<ImportedMaterial> materials;
  std::vector<ImportedPiece> pieces;
};

// `name` (may be empty) is the scene.json name for the file's pieces: a lone
// piece takes it as is, several become "<name>/<piece>". Throws
// SceneLoader::LoadError when Assimp cannot read the file, when a colour is
// not finite, or when a referenced vertex is NaN/Inf after the transform.
// Vertex colours: glTF's COLOR_0 is linear by its specification and is taken
// as is; every other format's (PLY red/green/blue, OBJ `v x y z r g b`) are
// display colours by convention, sRGB-encoded, and are decoded to linear.
// Alpha is not read. A colour outside [0, 1] is clamped with one warning per
// file; a non-finite one is an error.
ImportedFile import_mesh_file(const std::filesystem::path& file, const glm::dmat4& transform,
                              const std::string& name, Diagnostics& diagnostics);

}  // namespace bounce::scene_internal
