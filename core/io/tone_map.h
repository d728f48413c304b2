#pragma once
// Tone mapping shared by every 8-bit output of linear light (PLY vertex
// colours, camera PNGs): one exposure that maps the 99th percentile of
// luminance to 0.9, so a few very bright values (the light itself, a hot
// spot) clip instead of darkening everything else, then the sRGB transfer
// curve, so viewers that assume sRGB show the light as it is.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bounce {

// Rec. 709 / sRGB luminance of linear RGB.
inline float luminance(const glm::vec3& c) { return 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b; }

struct ToneMap {
  static constexpr double kPercentile = 0.99;
  static constexpr float kTarget = 0.9f;

  // Multiplier for linear values: kTarget / (kPercentile quantile of
  // `luminance`). Falls back to the maximum when the quantile is zero (mostly
  // dark data) and to 1 when everything is zero or the list is empty.
  static float exposure_for(std::vector<float> luminance);
  // The same for linear RGB values (their luminance).
  static float exposure_for(const std::vector<glm::vec3>& linear);

  // Linear value in [0, 1] (clamped) to an 8-bit sRGB code, rounded.
  static std::uint8_t srgb8(float linear);
};

}  // namespace bounce
