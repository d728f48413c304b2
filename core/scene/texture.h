#pragma once
// A colour texture in linear RGB with its MIP pyramid, read once per image
// (a file, or one embedded in a mesh file: scene/image_source.h) through
// OpenImageIO. 8- and 16-bit images (JPEG, PNG, ...) are sRGB-encoded
// unless the file says it is linear, so they are decoded to linear on load:
// averaging must happen on light, not on encoded values. Addressing wraps
// (the default of OBJ and glTF), and texture space has v up with image row 0
// at v = 1 (the convention Assimp gives for both formats).
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/image_source.h"

namespace bounce {

struct Texture {
  ImageSource source;  // where it was read from
  struct Level {
    int width = 0, height = 0;
    std::vector<glm::vec3> texels;  // row-major, row 0 at the top of the image
  };
  std::vector<Level> levels;  // levels[0] is the image; each next one half the size
  glm::vec3 mean{0.0f};       // of levels[0]: the albedo of a surface mapped once onto it

  // Bilinear lookup with wrapping at a (clamped) MIP level.
  glm::vec3 lookup(glm::vec2 uv, int level = 0) const;
  // The mean of the texture over a triangle of texture space (wrapping),
  // from a regular lattice of lookups at the MIP level whose texels match
  // the lattice spacing.
  glm::vec3 mean_over_triangle(const std::array<glm::vec2, 3>& uv) const;
};

// A colour texture weighted texel by texel: a masked material's colour over
// its solid part (weight 1 where the mask keeps a texel, 0 where it cuts it
// away; scene/alpha_mask.h). Holds the pyramids of texel x weight and of the
// weight, so that any mean over a footprint, at any level, is the mean of
// the weighted texels over the mean of the weights: the colour averaged over
// the weighted texels only, whatever colour the others hold.
struct WeightedTexture {
  Texture weighted;  // texel x weight
  Texture weight;    // the weight, in every channel
  // The weighted mean of the whole image; the plain mean where every weight
  // is 0.
  glm::vec3 mean{0.0f};

  // The numerator and denominator of the weighted mean at a point (bilinear)
  // or over a triangle of texture space (the lattice of
  // Texture::mean_over_triangle, the same for both): sums over several
  // triangles add up before the one division.
  struct Parts {
    glm::dvec3 weighted{0.0};
    double weight = 0.0;
  };
  Parts lookup(glm::vec2 uv) const;
  Parts mean_over_triangle(const std::array<glm::vec2, 3>& uv) const;
};

// `colour` weighted by `weights` (one per texel of its first level, row 0 at
// the top; negative ones count as 0).
std::shared_ptr<const WeightedTexture> weighted_texture(const Texture& colour,
                                                        const std::vector<float>& weights);

// An image's pixels as float, channels interleaved, as OpenImageIO
// reads them (not decoded from sRGB), and what the file says of them. Colour
// is unassociated (as stored, not multiplied by alpha): the colour of what
// is there, which a mask then cuts; alpha is as stored.
struct ImagePixels {
  int width = 0, height = 0, channels = 0;
  int alpha_channel = -1;  // the channel the file names alpha, -1 if none
  bool srgb = false;       // integer pixels not marked linear
  std::vector<float> pixels;
};
// Reads `source` whole; on failure returns nothing and sets `error` (the
// reason, without the source's name). Raw embedded texels are 8-bit sRGB
// RGBA, as a PNG of them would be.
std::optional<ImagePixels> read_image_pixels(const ImageSource& source, std::string& error);

// One sRGB-encoded component (in [0, 1]) decoded to linear, as 8- and
// 16-bit images are on load; also for per-vertex colours stored as display
// colours (PLY, OBJ).
float srgb_to_linear(float c);

// What a texture's texels are. Colours are decoded from sRGB when the file
// is sRGB-encoded (see above); directions (a normal map's 2 c - 1) are taken
// as stored whatever the file says: decoding would bend them.
enum class TexelKind { Colour, Direction };

// Reads and decodes `source`; null with `error` set when it cannot.
std::shared_ptr<const Texture> load_texture(const ImageSource& source, std::string& error,
                                            TexelKind kind = TexelKind::Colour);

// `name` as written in a material, relative to `folder` unless absolute.
// When no file has exactly that name, a file in the same folder whose name
// differs only in letter case is taken: models authored on Windows name
// their textures case-insensitively. nullopt when neither exists.
std::optional<std::filesystem::path> resolve_texture_path(const std::filesystem::path& folder,
                                                          const std::string& name);

}  // namespace bounce
