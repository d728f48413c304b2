#include "compress/compression_error.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace bounce {

namespace {

// For every light l and row k < count (exact row rows[k], or k when `rows` is
// empty; approximate row k): the area-weighted squares of (A~ - A) b_l and of
// A b_l, summed over the rows into err2[l] and ref2[l]. One pass over both
// matrices serves every light: each row pair is read from memory once and
// stays in cache while the lights go over it. Accumulated in double: a row
// of 16k products in float loses ~3 digits, more than the errors being
// measured.
void add_light_errors(const float* exact, const float* approx, std::size_t n, std::size_t count,
                      std::span<const std::uint32_t> rows, const std::vector<double>& b,
                      std::size_t lights, std::span<const float> area, std::vector<double>& err2,
                      std::vector<double>& ref2) {
  // Per row, then summed in row order: the same sums whatever the threads.
  std::vector<double> e(count * lights), r(count * lights);
#pragma omp parallel for schedule(static)
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t i = rows.empty() ? k : rows[k];
    const float* t = exact + i * n;
    const float* a = approx + k * n;
    for (std::size_t l = 0; l < lights; ++l) {
      const double* bl = b.data() + l * n;
      double d = 0.0, y = 0.0;
#pragma omp simd reduction(+ : d, y)
      for (std::size_t j = 0; j < n; ++j) {
        d += (static_cast<double>(a[j]) - static_cast<double>(t[j])) * bl[j];
        y += static_cast<double>(t[j]) * bl[j];
      }
      e[k * lights + l] = area[i] * d * d;
      r[k * lights + l] = area[i] * y * y;
    }
  }
  for (std::size_t k = 0; k < count; ++k)
    for (std::size_t l = 0; l < lights; ++l) {
      err2[l] += e[k * lights + l];
      ref2[l] += r[k * lights + l];
    }
}

void check_probe(const IndirectLightProbe& probe, std::size_t n, std::size_t channels) {
  if (probe.area.size() != n)
    throw Error("indirect-light error", "patch areas do not match the matrix size");
  for (const auto& b : probe.first_hit)
    if (b.size() != n) throw Error("indirect-light error", "a light vector has the wrong length");
  for (int c : probe.channel_of_rgb)
    if (c < 0 || static_cast<std::size_t>(c) >= channels)
      throw Error("indirect-light error", "colour channel mapped to a missing matrix");
}

}  // namespace

void IndirectLightError::add_light(double err2, double ref2) {
  if (!(ref2 > 0.0)) {  // this light puts no indirect light anywhere
    per_light.push_back(0.0);
    return;
  }
  const double rel = std::sqrt(err2 / ref2);
  per_light.push_back(rel);
  ++lights;
  rel_rms_sum += rel;
  rel_rms_max = std::max(rel_rms_max, rel);
  rel_rms_mean = rel_rms_sum / static_cast<double>(lights);
}

IndirectLightError indirect_light_error(const std::vector<const float*>& exact,
                                        const std::vector<const float*>& approx, std::size_t n,
                                        const IndirectLightProbe& probe) {
  return indirect_light_error_on_rows(exact, approx, n, {}, probe);
}

IndirectLightError indirect_light_error_on_rows(const std::vector<const float*>& exact,
                                                const std::vector<const float*>& approx,
                                                std::size_t n, std::span<const std::uint32_t> rows,
                                                const IndirectLightProbe& probe) {
  check_probe(probe, n, exact.size());
  const std::size_t lights = probe.first_hit.size();
  const std::size_t count = rows.empty() ? n : rows.size();
  std::vector<double> err2(lights, 0.0), ref2(lights, 0.0), b(lights * n);
  for (int k = 0; k < 3; ++k) {
    for (std::size_t l = 0; l < lights; ++l)
      for (std::size_t p = 0; p < n; ++p) b[l * n + p] = probe.first_hit[l][p][k];
    const auto c = static_cast<std::size_t>(probe.channel_of_rgb[static_cast<std::size_t>(k)]);
    add_light_errors(exact[c], approx[c], n, count, rows, b, lights, probe.area, err2, ref2);
  }
  IndirectLightError e;
  for (std::size_t l = 0; l < lights; ++l) e.add_light(err2[l], ref2[l]);
  return e;
}

CompressionErrors measure_compression(const std::vector<const float*>& exact,
                                      const CompressedMatrix& compressed,
                                      const IndirectLightProbe& probe,
                                      std::vector<float>* abs_error_sum, Progress* progress) {
  const std::size_t n = compressed.n;
  if (exact.size() != static_cast<std::size_t>(compressed.channels))
    throw Error("compression error", "exact and compressed matrices differ in channel count");
  if (abs_error_sum && compressed.sampled())
    throw Error("compression error", "a sample of rows has no error map of the whole matrix");
  CompressionErrors e;
  if (abs_error_sum) abs_error_sum->assign(n * n, 0.0f);
  // The rows the compression holds (every one unless sampled), and the exact
  // matrix's on them.
  const std::vector<std::uint32_t> rows =
      compressed.sampled() ? compressed.rows() : std::vector<std::uint32_t>{};
  const std::size_t count = compressed.sampled() ? rows.size() : n;
  std::vector<std::vector<float>> decoded(exact.size(), std::vector<float>(count * n));
  MatrixErrorAccumulator all;
  if (progress) progress->begin_stage("compress: measure errors", exact.size() + 1);
  for (std::size_t c = 0; c < exact.size(); ++c) {
    decompress_channel(compressed, static_cast<int>(c), decoded[c].data());
    std::vector<float> exact_rows;
    const float* exact_c = exact[c];
    if (!rows.empty()) {
      exact_rows.resize(count * n);
      for (std::size_t k = 0; k < count; ++k)
        std::copy_n(exact[c] + std::size_t{rows[k]} * n, n, exact_rows.data() + k * n);
      exact_c = exact_rows.data();
    }
    MatrixErrorAccumulator one;
    one.add(exact_c, decoded[c].data(), count * n);
    all.add(exact_c, decoded[c].data(), count * n);
    e.channels.push_back(one.result());
    if (abs_error_sum)
      for (std::size_t k = 0; k < n * n; ++k)
        (*abs_error_sum)[k] += std::abs(decoded[c][k] - exact[c][k]);
    if (progress) progress->advance();
  }
  e.matrix = all.result();
  std::vector<const float*> approx;
  for (const auto& d : decoded) approx.push_back(d.data());
  e.indirect = indirect_light_error_on_rows(exact, approx, n, rows, probe);
  if (progress) {
    progress->advance();
    progress->end_stage();
  }
  return e;
}

}  // namespace bounce
