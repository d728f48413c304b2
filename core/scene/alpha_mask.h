#pragma once
// The coverage of an alpha-masked (cut-out) material: one value per texel,
// read once per image (a file, or one embedded in a mesh file) through
// OpenImageIO, compared against the material's cutoff where a ray lands.
// Where the value is below the cutoff the surface is not there: rays pass,
// and no sample or patch stands on it. Values are taken as stored (alpha is
// linear in every format we read, and a grey mask is a coverage, not a
// colour), in [0, 1]. Addressing is the colour texture's: wrapping, v up,
// image row 0 at v = 1.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/image_source.h"

namespace bounce {

struct AlphaMask {
  ImageSource source;  // where it was read from; none for a constant
  int width = 0, height = 0;
  std::vector<float> values;  // row-major, row 0 at the top of the image

  // Bilinear lookup with wrapping; 1 (solid) where uv is not finite, so
  // that a triangle without texture coordinates stays whole (a mask of one
  // texel answers its value everywhere).
  float lookup(glm::vec2 uv) const;
  // The fraction of a triangle of texture space where lookup() * factor >=
  // cutoff, from a regular lattice of 16 to 256 lookups (one per
  // sub-triangle of a k x k split, k four times the texels across, 4 to 16).
  float solid_fraction(const std::array<glm::vec2, 3>& uv, float factor, float cutoff) const;
  // A mask of one texel: a constant coverage (glTF alpha without a texture).
  static std::shared_ptr<const AlphaMask> constant(float value);
  // One texel: the same everywhere, so it needs no texture coordinates.
  bool is_constant() const { return width == 1 && height == 1; }
};

struct Texture;
struct WeightedTexture;

// `colour` over the part of it `mask` keeps: each texel weighted 1 where
// mask x factor >= cutoff at its centre (the mask looked up in the colour
// texture's addressing, whatever its own size), else 0. A masked material's
// albedo is the mean over this: the surface that exists is the solid part,
// and the colour its holes hold (black, or whatever the painter left) is
// not on any surface.
std::shared_ptr<const WeightedTexture> solid_part(const Texture& colour, const AlphaMask& mask,
                                                  float factor, float cutoff);

// Which channel holds the coverage.
enum class AlphaSource {
  // OBJ map_d: the alpha channel when the image has one, else the grey
  // value (the mean of its colour channels).
  AlphaOrGrey,
  // glTF base colour texture: its alpha channel; 1 without one.
  AlphaOnly,
};

// Reads `file` (or the embedded image); null with `error` set when it cannot.
std::shared_ptr<const AlphaMask> load_alpha_mask(const ImageSource& file, AlphaSource source,
                                                 std::string& error);

}  // namespace bounce
