#include "block_bench.h"

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <limits>
#include <string>

#include "base/error.h"
#include "compress/block_image.h"
#include "compress/codec.h"
#include "compress/log_quantizer.h"
#include "compress/sparse_split.h"

namespace bounce {

BlockBenchData make_block_bench_data(std::size_t n) {
  if (n == 0 || n % 4 != 0)
    throw Error("block bench data",
                "size " + std::to_string(n) + " is not a positive multiple of 4");
  BlockBenchData data;
  data.n = n;
  data.rgb.assign(n * n * 3, 0);
  data.weights.assign(n * n * 3, 0.0f);
  std::vector<float> channel(n * n);
  for (int c = 0; c < 3; ++c) {
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t i = 0; i < static_cast<std::ptrdiff_t>(n); ++i) {
      const double di = static_cast<double>(i);
      for (std::size_t j = 0; j < n; ++j) {
        const double dj = static_cast<double>(j);
        const double v = std::exp(-std::abs(di - dj) / 200.0) *
                         (1.0 + 0.3 * std::sin(di / 37.0) * std::cos(dj / 53.0));
        // Albedo-like channel factors, not proportional to each other, so the
        // three channels are correlated but not identical (as R, G, B of T).
        const double albedo = c == 0   ? 0.8 * (1.0 + 0.2 * std::sin(di / 91.0))
                              : c == 1 ? 0.5 * (1.0 + 0.2 * std::cos(dj / 77.0))
                                       : 0.3;
        channel[static_cast<std::size_t>(i) * n + j] = static_cast<float>(v * albedo);
      }
    }
    const float threshold = kept_threshold(channel.data(), n, kPaperKeptFraction);
    LogQuantizer quantizer;
    for (const float v : channel)
      if (v < threshold) quantizer.vmax = std::max(quantizer.vmax, v);
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t k = 0; k < static_cast<std::ptrdiff_t>(n * n); ++k) {
      const float v = channel[k];
      const std::size_t at = static_cast<std::size_t>(k) * 3 + c;
      if (v >= threshold) continue;  // kept exactly: a hole (code 0, weight 0)
      const std::uint8_t q = quantizer.encode(v);
      data.rgb[at] = q;
      data.weights[at] = quantizer.weight(q);
    }
  }
  return data;
}

std::vector<BlockEncoderTiming> bench_bc1_encoders(std::size_t width, std::size_t height,
                                                   std::span<const std::uint8_t> rgb,
                                                   std::span<const float> weights,
                                                   std::span<const Bc1Encoder> encoders) {
  std::vector<BlockEncoderTiming> results;
  const double blocks = static_cast<double>(width / 4) * static_cast<double>(height / 4);
  for (const Bc1Encoder encoder : encoders) {
    BlockEncoderTiming r;
    r.encoder = bc1_encoder_name(encoder);
#ifdef _OPENMP
    r.threads = omp_get_max_threads();
#endif
    const std::clock_t cpu_start = std::clock();
    const auto start = std::chrono::steady_clock::now();
    const std::vector<std::uint8_t> out = encode_bc1_image(width, height, rgb, weights, encoder);
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    r.blocks_per_second = r.seconds > 0.0 ? blocks / r.seconds : 0.0;
    r.blocks_per_cpu_second = r.cpu_seconds > 0.0 ? blocks / r.cpu_seconds : 0.0;
    r.error = bc1_image_error(width, height, rgb, weights, out);
    results.push_back(r);
  }
  double reference = results.empty() ? 0.0 : results.front().error;
  for (std::size_t k = 0; k < results.size(); ++k)
    if (encoders[k] == Bc1Encoder::kSquishClusterFit) reference = results[k].error;
  for (BlockEncoderTiming& r : results)
    r.error_ratio = reference > 0.0 ? r.error / reference
                    : r.error > 0.0 ? std::numeric_limits<double>::infinity()
                                    : 1.0;
  return results;
}

}  // namespace bounce
