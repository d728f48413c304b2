#pragma once
// The log step of the published compression (paper 000, section 4.2): values
// below the kept threshold are divided by their maximum, their logarithm is
// taken, 25 is added and [0, 25] is scaled to [0, 255]:
//   q = round(255 (ln(v / vmax) + R) / R),  R = 25,  clamped to [0, 255];
//   v = 0 (and anything below vmax e^-R) -> q = 0, which decodes to 0.
// Decoding: v = vmax exp(q R / 255 - R) for q > 0.
// One code step is a relative step of R/255 = 9.8% in value: the error after
// decoding is proportional to the value, so an encoder that minimises the
// error in value space weights a code error by v^2 (see weight()).
#include <cmath>
#include <cstdint>

namespace bounce {

struct LogQuantizer {
  float vmax = 0.0f;    // largest value of the dense remainder
  float range = 25.0f;  // R: natural-log decades covered by codes 1..255

  std::uint8_t encode(float v) const {
    if (!(v > 0.0f) || !(vmax > 0.0f)) return 0;
    const float q = std::round(255.0f * (std::log(v / vmax) + range) / range);
    return static_cast<std::uint8_t>(q < 0.0f ? 0.0f : (q > 255.0f ? 255.0f : q));
  }
  float decode(std::uint8_t q) const {
    return q == 0 ? 0.0f : vmax * std::exp(static_cast<float>(q) * range / 255.0f - range);
  }
  // d(value)/d(code) at code q, squared: how much a code error costs after
  // decoding. Zero for q = 0 is wrong (a zero decoded as 1 costs decode(1)),
  // so the weight of a zero is that of code 1.
  float weight(std::uint8_t q) const {
    const float slope = decode(q == 0 ? 1 : q) * range / 255.0f;
    return slope * slope;
  }
};

}  // namespace bounce
