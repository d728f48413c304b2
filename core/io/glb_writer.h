#pragma once
// Lit triangle meshes as binary glTF 2.0 (.glb), the standard exchange format
// Blender, three.js, Babylon and every glTF viewer open without a plug-in.
// Each primitive holds
//   POSITION, NORMAL     float VEC3 per vertex;
//   TEXCOORD_0           float VEC2, when the primitive has texture
//                        coordinates (glTF's convention: v down, (0, 0) the
//                        top-left corner of the image);
//   COLOR_0              float VEC3, its light times the model's exposure,
//                        clamped to [0, 1] and kept linear (glTF vertex
//                        colours are linear; the viewer applies the display's
//                        transfer curve itself);
//   _RADIANCE            float VEC3, the exact linear light leaving the
//                        surface (an application attribute, ignored by
//                        viewers, read by scripts);
//   indices              unsigned int, counter-clockwise = front.
// Materials are unlit (KHR_materials_unlit), so a viewer shows the baked
// light itself instead of shading it again under its own lamps: what it draws
// is baseColorFactor x baseColorTexture x COLOR_0. Images are embedded in the
// binary chunk as PNG or JPEG bytes. Written through AtomicFile: a reader
// never sees half a file.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

struct GlbMeshView {
  const std::vector<glm::vec3>& positions;
  const std::vector<glm::vec3>& normals;   // one per position, unit
  const std::vector<glm::vec3>& radiance;  // one per position, linear
  const std::vector<glm::uvec3>& triangles;
  std::string name = "lit";  // the node's and mesh's name in the viewer's outliner
};

// An encoded image file's bytes.
struct GlbImage {
  std::string name;
  std::string mime_type;  // "image/png" or "image/jpeg"
  std::vector<std::uint8_t> bytes;
};

struct GlbMaterial {
  std::string name;
  glm::vec4 base_color{1.0f};  // linear RGB and alpha
  // Index into GlbModel::images of the base colour texture (sRGB colour,
  // alpha in its alpha channel); none: the factor alone.
  std::optional<std::size_t> base_color_image;
  // Set: alphaMode MASK, the surface is there where alpha >= this cutoff.
  std::optional<float> alpha_cutoff;
};

struct GlbPrimitive {
  std::size_t material = 0;  // index into GlbModel::materials
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // one per position
  std::vector<glm::vec2> uv;        // empty, or one per position (glTF's convention)
  std::vector<glm::vec3> light;     // one per position: COLOR_0 before exposure and clamping
  std::vector<glm::vec3> radiance;  // one per position: _RADIANCE
  std::vector<glm::uvec3> triangles;
};

struct GlbModel {
  std::string name = "lit";  // the node's and mesh's name in the viewer's outliner
  float exposure = 1.0f;     // COLOR_0 = clamp(light x exposure, 0, 1)
  // What COLOR_0 holds, for a reader of the file (asset.extras.colours).
  std::string colours;
  std::vector<GlbImage> images;
  std::vector<GlbMaterial> materials;
  std::vector<GlbPrimitive> primitives;
};

// Writes `model`. Throws IoError (io/atomic_file.h) when the file cannot be
// written, bounce::Error when the arrays do not fit together, hold NaN/Inf, a
// primitive is empty, an index is out of range or the file would exceed the
// format's 4 GiB.
void write_glb(const std::filesystem::path& path, const GlbModel& model);

// One mesh without textures: a single primitive on a white unlit material
// whose COLOR_0 is the radiance tone-mapped with the PLY's exposure
// (io/tone_map.h). Returns that exposure.
float write_lit_glb(const std::filesystem::path& path, const GlbMeshView& mesh);

}  // namespace bounce
