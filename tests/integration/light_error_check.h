#pragma once
// The indirect-light error of a compressed bake recomputed from its files
// alone, with code independent of the library's: the exact T.npy, a decoded
// T~ (any decoder), lights_first_hit.npy, the area column of patches.npy and
// transport.channel_of_rgb of the manifest. Per light,
//   e = sqrt(sum_p A_p sum_k ((T~_c(k) b_k)_p - (T_c(k) b_k)_p)^2)
//     / sqrt(sum_p A_p sum_k (T_c(k) b_k)_p^2),
// over the lights with any indirect light; reported as mean and max.
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "cli_harness.h"
#include "decoded_bake.h"

namespace bounce::itest {

struct LightProbeFiles {
  std::size_t n = 0;
  std::vector<std::vector<double>> b;  // per light: n x 3, patch-major
  std::vector<double> area;
  std::array<int, 3> channel{0, 1, 2};
};

inline LightProbeFiles read_light_probe(const fs::path& bake, const json& manifest) {
  LightProbeFiles p;
  const NpyArray<float> patches = read_npy_f32(bake / "patches.npy");
  p.n = patches.shape.at(0);
  constexpr std::size_t kAreaColumn = 6;  // docs/bake-format.md, patches.npy columns
  for (std::size_t i = 0; i < p.n; ++i) p.area.push_back(at(patches, i, kAreaColumn));
  const NpyArray<float> lights = read_npy_f32(bake / "lights_first_hit.npy");
  EXPECT_EQ(lights.shape.at(1), p.n);
  for (std::size_t l = 0; l < lights.shape.at(0); ++l)
    p.b.emplace_back(lights.data.begin() + static_cast<std::ptrdiff_t>(l * p.n * 3),
                     lights.data.begin() + static_cast<std::ptrdiff_t>((l + 1) * p.n * 3));
  const json& map = manifest.at("transport").at("channel_of_rgb");
  for (std::size_t k = 0; k < 3; ++k) p.channel[k] = map.at(k).get<int>();
  return p;
}

// (T b_k)_i for colour k of light vector b (n x 3).
inline std::vector<double> times(const float* t, std::size_t n, const std::vector<double>& b,
                                 int k) {
  std::vector<double> y(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    double s = 0.0;
    for (std::size_t j = 0; j < n; ++j) s += static_cast<double>(t[i * n + j]) * b[3 * j + k];
    y[i] = s;
  }
  return y;
}

struct RecomputedLightError {
  std::size_t lights = 0;
  double mean = 0.0, max = 0.0;
};

// `exact` and `approx`: stored channel c at [c].
inline RecomputedLightError recompute_light_error(const std::vector<const float*>& exact,
                                                  const std::vector<const float*>& approx,
                                                  const LightProbeFiles& p) {
  RecomputedLightError r;
  double sum = 0.0;
  for (const auto& b : p.b) {
    double err2 = 0.0, ref2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const auto c = static_cast<std::size_t>(p.channel[static_cast<std::size_t>(k)]);
      const std::vector<double> y = times(exact[c], p.n, b, k);
      const std::vector<double> y_approx = times(approx[c], p.n, b, k);
      for (std::size_t i = 0; i < p.n; ++i) {
        err2 += p.area[i] * (y_approx[i] - y[i]) * (y_approx[i] - y[i]);
        ref2 += p.area[i] * y[i] * y[i];
      }
    }
    if (!(ref2 > 0.0)) continue;
    const double e = std::sqrt(err2 / ref2);
    ++r.lights;
    sum += e;
    r.max = std::max(r.max, e);
  }
  if (r.lights > 0) r.mean = sum / static_cast<double>(r.lights);
  return r;
}

// The whole recomputation for a compressed bake folder made with
// --dump-matrices: T.npy against T~ decoded by decode_bake.
inline RecomputedLightError recompute_light_error_of_bake(const fs::path& bake,
                                                          const json& manifest) {
  const Decoded d = decode_bake(bake, manifest.at("compression"));
  const NpyArray<float> exact = read_npy_f32(bake / "T.npy");
  EXPECT_EQ(exact.shape, (std::vector<std::size_t>{d.channels.size(), d.n, d.n}));
  std::vector<const float*> exact_matrices, decoded;
  for (std::size_t c = 0; c < d.channels.size(); ++c) {
    exact_matrices.push_back(exact.data.data() + c * d.n * d.n);
    decoded.push_back(d.channels[c].data());
  }
  return recompute_light_error(exact_matrices, decoded, read_light_probe(bake, manifest));
}

}  // namespace bounce::itest
