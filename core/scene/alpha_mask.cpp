#include "scene/alpha_mask.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "scene/texture.h"

namespace bounce {

namespace {

float value(const AlphaMask& m, int x, int y) {
  x %= m.width;
  y %= m.height;
  if (x < 0) x += m.width;
  if (y < 0) y += m.height;
  return m.values[static_cast<std::size_t>(y) * static_cast<std::size_t>(m.width) +
                  static_cast<std::size_t>(x)];
}

}  // namespace

float AlphaMask::lookup(glm::vec2 uv) const {
  if (is_constant()) return values.front();
  // Texel centres at half-integers, as Texture::lookup.
  const float x = uv.x * static_cast<float>(width) - 0.5f;
  const float y = (1.0f - uv.y) * static_cast<float>(height) - 0.5f;
  if (!std::isfinite(x) || !std::isfinite(y)) return 1.0f;
  const float xw = x - static_cast<float>(width) * std::floor(x / static_cast<float>(width));
  const float yw = y - static_cast<float>(height) * std::floor(y / static_cast<float>(height));
  const float fx = std::floor(xw), fy = std::floor(yw);
  const int x0 = static_cast<int>(fx), y0 = static_cast<int>(fy);
  const float ax = xw - fx, ay = yw - fy;
  return (1.0f - ay) * ((1.0f - ax) * value(*this, x0, y0) + ax * value(*this, x0 + 1, y0)) +
         ay * ((1.0f - ax) * value(*this, x0, y0 + 1) + ax * value(*this, x0 + 1, y0 + 1));
}

float AlphaMask::solid_fraction(const std::array<glm::vec2, 3>& uv, float factor,
                                float cutoff) const {
  const glm::vec2 scale(static_cast<float>(width), static_cast<float>(height));
  const glm::vec2 e1 = (uv[1] - uv[0]) * scale, e2 = (uv[2] - uv[0]) * scale;
  const float texels = 0.5f * std::abs(e1.x * e2.y - e1.y * e2.x);
  if (!std::isfinite(texels)) return lookup(uv[0]) * factor >= cutoff ? 1.0f : 0.0f;
  // Four lookups across a texel at least: a mask's edges run through its
  // texels (where the bilinear value crosses the cutoff), not along them.
  constexpr int kMinDivisions = 4, kMaxDivisions = 16;
  const int k = std::clamp(static_cast<int>(std::ceil(4.0f * std::sqrt(texels))), kMinDivisions,
                           kMaxDivisions);
  int solid = 0;
  const float inv = 1.0f / static_cast<float>(k);
  const auto at = [&](float a, float b) {
    const glm::vec2 p = uv[0] + a * inv * (uv[1] - uv[0]) + b * inv * (uv[2] - uv[0]);
    if (lookup(p) * factor >= cutoff) ++solid;
  };
  for (int i = 0; i < k; ++i)
    for (int j = 0; i + j < k; ++j) {
      at(static_cast<float>(i) + 1.0f / 3.0f, static_cast<float>(j) + 1.0f / 3.0f);
      if (i + j < k - 1)
        at(static_cast<float>(i) + 2.0f / 3.0f, static_cast<float>(j) + 2.0f / 3.0f);
    }
  return static_cast<float>(solid) / static_cast<float>(k * k);
}

std::shared_ptr<const AlphaMask> AlphaMask::constant(float value) {
  auto mask = std::make_shared<AlphaMask>();
  mask->width = mask->height = 1;
  mask->values = {value};
  return mask;
}

std::shared_ptr<const WeightedTexture> solid_part(const Texture& colour, const AlphaMask& mask,
                                                  float factor, float cutoff) {
  const Texture::Level& base = colour.levels.front();
  std::vector<float> solid;
  solid.reserve(base.texels.size());
  for (int y = 0; y < base.height; ++y)
    for (int x = 0; x < base.width; ++x) {
      // Texel centres at half-integers, row 0 at v = 1 (Texture::lookup).
      const glm::vec2 uv((static_cast<float>(x) + 0.5f) / static_cast<float>(base.width),
                         1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(base.height));
      solid.push_back(mask.lookup(uv) * factor >= cutoff ? 1.0f : 0.0f);
    }
  return weighted_texture(colour, solid);
}

std::shared_ptr<const AlphaMask> load_alpha_mask(const ImageSource& file, AlphaSource source,
                                                 std::string& error) {
  const std::optional<ImagePixels> image = read_image_pixels(file, error);
  if (!image) return nullptr;
  const int w = image->width, h = image->height, channels = image->channels;
  const std::vector<float>& pixels = image->pixels;
  // The alpha channel: as the file names it, else the last of two or four.
  int alpha = image->alpha_channel;
  if (alpha < 0 && (channels == 2 || channels == 4)) alpha = channels - 1;
  const int colours = alpha >= 0 ? std::min(alpha, 3) : std::min(channels, 3);
  auto mask = std::make_shared<AlphaMask>();
  mask->source = file;
  mask->width = w;
  mask->height = h;
  mask->values.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (std::size_t p = 0; p < mask->values.size(); ++p) {
    const float* px = &pixels[p * static_cast<std::size_t>(channels)];
    float v = 1.0f;
    if (alpha >= 0) {
      v = px[alpha];
    } else if (source == AlphaSource::AlphaOrGrey && colours > 0) {
      v = 0.0f;
      for (int c = 0; c < colours; ++c) v += px[c];
      v /= static_cast<float>(colours);
    }
    mask->values[p] = std::isfinite(v) ? std::clamp(v, 0.0f, 1.0f) : 0.0f;
  }
  return mask;
}

}  // namespace bounce
