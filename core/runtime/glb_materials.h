#pragma once
// A scene's materials as glTF materials for a lit mesh (io/glb_writer.h).
//
// A material with a colour texture (and texture coordinates) becomes a glTF
// material of its own: baseColorFactor = its texture factor, and the texture
// as baseColorTexture. Its vertex colours then hold the light without the
// albedo, so that what a viewer draws, factor x texel x COLOR_0, is the
// albedo at each point times the light reaching it. An emitting material is
// the exception: its look is its emission, so it stays with the plain ones.
//
// An alpha-masked material becomes a material of its own with alphaMode
// MASK, its cutoff and alpha factor; glTF reads the coverage from the base
// colour texture's alpha, so the image carries the mask as its alpha.
//
// Every other material shares one plain white material, index 0, "baked
// light": its vertex colours hold the whole light, albedo included.
//
// Images are embedded as the original image's bytes (its file's, or the
// bytes a mesh file embedded it as) when they are PNG or JPEG and already
// hold what glTF reads (the colour, and for a mask the
// coverage in its alpha channel); otherwise they are encoded as 8-bit PNG:
// the texture's colour as its file stores it (integer sRGB values kept,
// linear values encoded to sRGB) and the mask's values, looked up at the
// image's texel centres, as alpha.
#include <cstddef>
#include <optional>
#include <vector>

#include "io/glb_writer.h"
#include "scene/scene.h"

namespace bounce {

struct GlbMaterials {
  std::vector<GlbImage> images;
  std::vector<GlbMaterial> materials;  // [0]: the plain "baked light" material
  // Per scene material: its glTF material (0 for the plain ones).
  std::vector<std::size_t> of_scene_material;
  // Per scene material: whether its vertex colours hold the light without
  // the albedo (it has a texture that carries the albedo).
  std::vector<bool> textured;
};

// The glTF materials of the scene materials flagged in `used` (one flag per
// scene material; unused ones map to the plain material and embed nothing).
// Throws bounce::Error naming the image file when it cannot be read again.
GlbMaterials glb_materials(const Scene& scene, const std::vector<bool>& used);

}  // namespace bounce
