#include "io/tone_map.h"

#include <algorithm>
#include <cmath>

namespace bounce {

float ToneMap::exposure_for(std::vector<float> luminance) {
  // NaN or negative luminance would make the quantile meaningless; they are
  // not light, so they count as black.
  for (float& l : luminance)
    if (!(l > 0.0f)) l = 0.0f;
  if (luminance.empty()) return 1.0f;
  const auto k = static_cast<std::size_t>(
      std::floor(kPercentile * static_cast<double>(luminance.size() - 1) + 0.5));
  std::nth_element(luminance.begin(), luminance.begin() + static_cast<std::ptrdiff_t>(k),
                   luminance.end());
  float reference = luminance[k];
  if (!(reference > 0.0f)) reference = *std::max_element(luminance.begin(), luminance.end());
  if (!(reference > 0.0f) || !std::isfinite(reference)) return 1.0f;
  return kTarget / reference;
}

float ToneMap::exposure_for(const std::vector<glm::vec3>& linear) {
  std::vector<float> lum;
  lum.reserve(linear.size());
  for (const glm::vec3& c : linear) lum.push_back(luminance(c));
  return exposure_for(std::move(lum));
}

std::uint8_t ToneMap::srgb8(float linear) {
  // NaN counts as black, +inf as white.
  const float c = linear > 0.0f ? std::min(linear, 1.0f) : 0.0f;
  // IEC 61966-2-1: linear segment near black, power 1/2.4 above.
  const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
  return static_cast<std::uint8_t>(std::lround(255.0f * std::clamp(s, 0.0f, 1.0f)));
}

}  // namespace bounce
