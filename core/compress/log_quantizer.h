#pragma once
// The log step of the published compression: values
// below the kept threshold are divided by their maximum, their logarithm is
// taken, 25 is added and [0, 25] is scaled to [0, 255]:
//   q = round(255 (ln(v / vmax) + R) / R),  R = 25,  clamped to [0, 255];
//   v = 0 (and anything below vmax e^-R) -> q = 0, which decodes to 0.
// Decoding: v = vmax exp(q R / 255 - R) for q > 0.
// One code step is a relative step of R/255 = 9.8% in value: the error after
// decoding is proportional to the value, so an encoder that minimises the
// error in value space weights a code error by v^2 (see weight()).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bounce {

struct LogQuantizer {
  float vmax = 0.0f;    // largest value of the dense remainder
  float range = 25.0f;  // R: natural-log decades covered by codes 1..255

  // Ours: a value is coded 0 (zero) only when zero is nearer to it than
  // code 1 is; the paper codes 0 everything that rounds below 0.5 in the log
  // domain, up to half a code step above the bottom of the range.
  bool nearest_at_zero = false;

  std::uint8_t encode(float v) const { return encode(v, 0.5f * decode(1)); }
  // The same with `half_code_one` = 0.5 decode(1) given: a loop over many
  // values takes its exp once.
  std::uint8_t encode(float v, float half_code_one) const {
    if (!(v > 0.0f) || !(vmax > 0.0f)) return 0;
    const float q = std::round(255.0f * (std::log(v / vmax) + range) / range);
    if (q < 1.0f && nearest_at_zero) return v >= half_code_one ? 1 : 0;
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

// Ours: a log range fitted to the values instead of the paper's fixed 25. A
// code step is a relative step of range/255 in value, and every code error of
// the block encoder is paid in that unit, so a range no wider than the values
// need shrinks every error after decoding by 25/range. The range reaches
// down to the `low_quantile` of the positive values (a sample of them);
// anything smaller decodes to 0 or the smallest code, an error below
// vmax e^-range each.
inline float fitted_log_range(const float* values, std::size_t count, float vmax,
                              double low_quantile) {
  if (!(vmax > 0.0f)) return 25.0f;
  // At most ~1M values, evenly strided: the quantile of a large sample.
  const std::size_t stride = count / (1u << 20) + 1;
  std::vector<float> positive;
  positive.reserve(count / stride + 1);
  for (std::size_t k = 0; k < count; k += stride)
    if (values[k] > 0.0f && values[k] <= vmax) positive.push_back(values[k]);
  if (positive.empty()) return 25.0f;
  const auto at = static_cast<std::size_t>(low_quantile * static_cast<double>(positive.size() - 1));
  std::nth_element(positive.begin(), positive.begin() + static_cast<std::ptrdiff_t>(at),
                   positive.end());
  const float range = std::log(vmax / positive[at]);
  return range < 1.0f ? 1.0f : (range > 25.0f ? 25.0f : range);
}

}  // namespace bounce
