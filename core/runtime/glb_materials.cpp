#include "runtime/glb_materials.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "base/error.h"
#include "io/png_encode.h"
#include "io/tone_map.h"
#include "scene/alpha_mask.h"
#include "scene/texture.h"

namespace bounce {

namespace {

// The image's file bytes, as its file (or the mesh file it is embedded in)
// stores them; empty for raw embedded texels, which have no file to copy.
std::vector<std::uint8_t> file_bytes(const ImageSource& source) {
  if (source.is_embedded() && source.embedded()->raw()) return {};
  std::string error;
  std::vector<std::uint8_t> bytes = image_file_bytes(source, error);
  if (bytes.empty())
    throw Error(source.name(),
                "cannot read the image again to embed it in the glTF file: " + error);
  return bytes;
}

bool starts_with(const std::vector<std::uint8_t>& bytes,
                 std::initializer_list<std::uint8_t> magic) {
  return bytes.size() >= magic.size() && std::equal(magic.begin(), magic.end(), bytes.begin());
}
bool is_png(const std::vector<std::uint8_t>& b) {
  return starts_with(b, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'});
}
bool is_jpeg(const std::vector<std::uint8_t>& b) { return starts_with(b, {0xff, 0xd8, 0xff}); }

// An image file's pixels as 8-bit codes for a glTF base colour (sRGB).
struct Rgb8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // width x height x 3
};

Rgb8 colour_codes(const ImageSource& source) {
  std::string error;
  const std::optional<ImagePixels> image = read_image_pixels(source, error);
  if (!image) throw Error(source.name(), "cannot read the texture again to embed it: " + error);
  Rgb8 out{image->width, image->height, {}};
  const auto texels =
      static_cast<std::size_t>(image->width) * static_cast<std::size_t>(image->height);
  const auto channels = static_cast<std::size_t>(image->channels);
  out.rgb.reserve(texels * 3);
  for (std::size_t p = 0; p < texels; ++p)
    for (std::size_t c = 0; c < 3; ++c) {
      // One or two channels: grey (and alpha); three or more: RGB first.
      float v = image->pixels[p * channels + (channels >= 3 ? c : 0)];
      if (!std::isfinite(v)) v = 0.0f;
      out.rgb.push_back(
          image->srgb ? static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f))
                      : ToneMap::srgb8(v));
    }
  return out;
}

// An RGBA image: the texture's colour (white when the material's colour is
// not a texture) and the mask's coverage, looked up at the texel centres, as
// alpha.
GlbImage masked_image(const Material& m, bool textured) {
  Rgb8 colour;
  if (textured) {
    colour = colour_codes(m.texture->source);
  } else {
    colour.width = m.alpha_mask->width;
    colour.height = m.alpha_mask->height;
    colour.rgb.assign(
        static_cast<std::size_t>(colour.width) * static_cast<std::size_t>(colour.height) * 3, 255);
  }
  const int w = colour.width, h = colour.height;
  std::vector<std::uint8_t> rgba;
  rgba.reserve(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 4);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      // Texture space has v up with image row 0 at v = 1.
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(w),
                         1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(h));
      const std::size_t p =
          static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
      for (std::size_t c = 0; c < 3; ++c) rgba.push_back(colour.rgb[p * 3 + c]);
      const float coverage = std::clamp(m.alpha_mask->lookup(uv), 0.0f, 1.0f);
      rgba.push_back(static_cast<std::uint8_t>(std::lround(coverage * 255.0f)));
    }
  const std::string what = (textured ? m.texture->source : m.alpha_mask->source).name();
  return {m.name, "image/png", encode_png(w, h, 4, rgba, what)};
}

GlbImage colour_image(const Material& m) {
  const ImageSource& source = m.texture->source;
  std::vector<std::uint8_t> bytes = file_bytes(source);
  if (is_png(bytes)) return {m.name, "image/png", std::move(bytes)};
  if (is_jpeg(bytes)) return {m.name, "image/jpeg", std::move(bytes)};
  const Rgb8 colour = colour_codes(source);
  return {m.name, "image/png",
          encode_png(colour.width, colour.height, 3, colour.rgb, source.name())};
}

// Whether the texture image itself carries the mask: the same image, PNG
// (JPEG has no alpha), with an alpha channel the mask was read from.
std::optional<GlbImage> image_holding_its_mask(const Material& m) {
  if (!m.texture || m.texture->source != m.alpha_mask->source) return std::nullopt;
  std::vector<std::uint8_t> bytes = file_bytes(m.texture->source);
  if (!is_png(bytes)) return std::nullopt;
  std::string error;
  const std::optional<ImagePixels> image = read_image_pixels(m.texture->source, error);
  if (!image || image->alpha_channel < 0) return std::nullopt;
  return GlbImage{m.name, "image/png", std::move(bytes)};
}

}  // namespace

GlbMaterials glb_materials(const Scene& scene, const std::vector<bool>& used) {
  GlbMaterials out;
  out.materials.push_back({"baked light", glm::vec4(1.0f), std::nullopt, std::nullopt});
  out.of_scene_material.assign(scene.materials.size(), 0);
  out.textured.assign(scene.materials.size(), false);
  const bool has_uv = !scene.triangle_uv.empty();
  for (std::size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    if (i >= used.size() || !used[i]) continue;
    const bool textured = has_uv && m.texture && !m.is_emissive();
    const bool masked = m.alpha_mask && (has_uv || m.alpha_mask->is_constant());
    if (!textured && !masked) continue;
    GlbMaterial g{m.name, glm::vec4(1.0f), std::nullopt, std::nullopt};
    if (textured) g.base_color = glm::vec4(m.texture_factor, 1.0f);
    std::optional<GlbImage> image;
    if (masked) {
      g.alpha_cutoff = m.alpha_cutoff;
      g.base_color.a = m.alpha_factor;
      // A constant coverage needs no image: it goes into the factor.
      if (m.alpha_mask->is_constant()) {
        g.base_color.a = m.alpha_factor * m.alpha_mask->values[0];
        if (textured) image = colour_image(m);
      } else {
        if (textured) image = image_holding_its_mask(m);
        if (!image) image = masked_image(m, textured);
      }
    } else {
      image = colour_image(m);
    }
    if (image) {
      g.base_color_image = out.images.size();
      out.images.push_back(std::move(*image));
    }
    out.of_scene_material[i] = out.materials.size();
    out.textured[i] = textured;
    out.materials.push_back(std::move(g));
  }
  return out;
}

}  // namespace bounce
