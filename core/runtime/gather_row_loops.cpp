#include "runtime/gather_row_loops.h"

#include <algorithm>

#include "base/error.h"
#include "runtime/block_loops.h"

namespace bounce::gather_loops {

namespace {

void compact_band_sse2(const CompactRows& r, std::size_t begin, std::size_t end, glm::vec3* out) {
  const CompactEntries entries{r.light, r.entry, r.count_bits, (1u << r.count_bits) - 1u};
  for (std::size_t row = begin; row < end; ++row)
    out[row] = sum_row(entries, r.first[row], r.first[row + 1], r.scale);
}

#ifdef BOUNCE_AVX2_BLOCK_LOOP
// GCC 12's AVX-512 intrinsics start their results from _mm512_undefined_*(),
// which -Wmaybe-uninitialized reports at every use; those values are fully
// overwritten, so the warning is off for these loops.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

// The wide loops take a row's entries a vector at a time: one load, one AND
// and one conversion give every entry's weight (its ray count); two (AVX2)
// or four (AVX-512) sources' 16-byte lights are loaded side by side into one
// register, and a permute spreads each entry's weight over its light's four
// lanes for one fused multiply-add. The sources are shifted out of the
// entries one by one as integers: shifting them in the vector and storing it
// to reload each lane made every reload wait on the store (on this machine
// the AVX2 loop took 7.6 ms on Sponza that way, 6.5 ms this way; the
// portable loop 8.4).

// The rest of a row, one entry at a time.
__attribute__((target("avx2,fma"))) inline __m128 tail_avx2(const CompactRows& r, std::uint64_t k,
                                                            std::uint64_t end, __m128 acc) {
  const std::uint32_t mask = (1u << r.count_bits) - 1u;
  for (; k < end; ++k) {
    const std::uint32_t e = r.entry[k];
    acc = _mm_fmadd_ps(_mm_set1_ps(static_cast<float>(e & mask)),
                       _mm_load_ps(r.light[e >> r.count_bits].c), acc);
  }
  return acc;
}

// Two sources' lights side by side.
__attribute__((target("avx2,fma"))) inline __m256 two(const float* light, std::uint32_t a,
                                                      std::uint32_t b) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(light + 4 * std::size_t{a})),
                              _mm_load_ps(light + 4 * std::size_t{b}), 1);
}

// Four sources' lights side by side.
__attribute__((target("avx512f,avx2,fma"))) inline __m512 four(const float* light,
                                                               const std::uint32_t* s) {
  __m512 l = _mm512_castps128_ps512(_mm_load_ps(light + 4 * std::size_t{s[0]}));
  l = _mm512_insertf32x4(l, _mm_load_ps(light + 4 * std::size_t{s[1]}), 1);
  l = _mm512_insertf32x4(l, _mm_load_ps(light + 4 * std::size_t{s[2]}), 2);
  return _mm512_insertf32x4(l, _mm_load_ps(light + 4 * std::size_t{s[3]}), 3);
}

__attribute__((target("avx2,fma"))) inline void store_row(__m128 sum, float scale, glm::vec3& out) {
  alignas(16) float e[4];
  _mm_store_ps(e, _mm_mul_ps(_mm_set1_ps(scale), sum));
  out = glm::vec3(e[0], e[1], e[2]);
}

// Entries k .. k + 7 into two accumulators.
__attribute__((target("avx2,fma,bmi2"))) inline void eight_avx2(const CompactRows& r,
                                                                std::uint64_t k, __m256& a0,
                                                                __m256& a1) {
  const __m256i mask = _mm256_set1_epi32(static_cast<int>((1u << r.count_bits) - 1u));
  const __m256i pair0 = _mm256_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1);
  const __m256i pair1 = _mm256_setr_epi32(2, 2, 2, 2, 3, 3, 3, 3);
  const __m256i pair2 = _mm256_setr_epi32(4, 4, 4, 4, 5, 5, 5, 5);
  const __m256i pair3 = _mm256_setr_epi32(6, 6, 6, 6, 7, 7, 7, 7);
  const float* light = r.light[0].c;
  const __m256i e = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(r.entry + k));
  const __m256 w = _mm256_cvtepi32_ps(_mm256_and_si256(e, mask));
  const std::uint32_t* x = r.entry + k;
  const int b = r.count_bits;
  std::uint32_t s[8] = {x[0] >> b, x[1] >> b, x[2] >> b, x[3] >> b,
                        x[4] >> b, x[5] >> b, x[6] >> b, x[7] >> b};
  a0 = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pair0), two(light, s[0], s[1]), a0);
  a1 = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pair1), two(light, s[2], s[3]), a1);
  a0 = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pair2), two(light, s[4], s[5]), a0);
  a1 = _mm256_fmadd_ps(_mm256_permutevar8x32_ps(w, pair3), two(light, s[6], s[7]), a1);
}

__attribute__((target("avx2,fma,bmi2"))) void compact_band_avx2(const CompactRows& r,
                                                                std::size_t begin, std::size_t end,
                                                                glm::vec3* out) {
  for (std::size_t row = begin; row < end; ++row) {
    std::uint64_t k = r.first[row];
    const std::uint64_t stop = r.first[row + 1];
    __m256 a0 = _mm256_setzero_ps(), a1 = _mm256_setzero_ps();
    for (; k + 8 <= stop; k += 8) eight_avx2(r, k, a0, a1);
    const __m256 a = _mm256_add_ps(a0, a1);
    const __m128 sum = _mm_add_ps(_mm256_castps256_ps128(a), _mm256_extractf128_ps(a, 1));
    store_row(tail_avx2(r, k, stop, sum), r.scale, out[row]);
  }
}

__attribute__((target("avx512f,avx2,fma,bmi2"))) void compact_band_avx512(const CompactRows& r,
                                                                          std::size_t begin,
                                                                          std::size_t end,
                                                                          glm::vec3* out) {
  const __m512i mask = _mm512_set1_epi32(static_cast<int>((1u << r.count_bits) - 1u));
  const __m512i quad0 = _mm512_setr_epi32(0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3);
  const __m512i quad1 = _mm512_add_epi32(quad0, _mm512_set1_epi32(4));
  const __m512i quad2 = _mm512_add_epi32(quad0, _mm512_set1_epi32(8));
  const __m512i quad3 = _mm512_add_epi32(quad0, _mm512_set1_epi32(12));
  const float* light = r.light[0].c;
  for (std::size_t row = begin; row < end; ++row) {
    std::uint64_t k = r.first[row];
    const std::uint64_t stop = r.first[row + 1];
    // One accumulator: lane j sums entries j, j + 4, j + 8, ... in order,
    // as the AVX2 loop's four 128-bit halves do, so that both loops give
    // the same sums to the bit and the one timed faster can be picked.
    __m512 a = _mm512_setzero_ps();
    for (; k + 16 <= stop; k += 16) {
      const __m512i e = _mm512_loadu_si512(r.entry + k);
      const __m512 w = _mm512_cvtepi32_ps(_mm512_and_si512(e, mask));
      const std::uint32_t* x = r.entry + k;
      const int b = r.count_bits;
      std::uint32_t s[16];
      for (int j = 0; j < 16; ++j) s[j] = x[j] >> b;
      a = _mm512_fmadd_ps(_mm512_permutexvar_ps(quad0, w), four(light, s), a);
      a = _mm512_fmadd_ps(_mm512_permutexvar_ps(quad1, w), four(light, s + 4), a);
      a = _mm512_fmadd_ps(_mm512_permutexvar_ps(quad2, w), four(light, s + 8), a);
      a = _mm512_fmadd_ps(_mm512_permutexvar_ps(quad3, w), four(light, s + 12), a);
    }
    // The AVX2 loop's two accumulators, then its rest of the row.
    __m256 a0 = _mm512_castps512_ps256(a),
           a1 = _mm256_castpd_ps(_mm512_extractf64x4_pd(_mm512_castps_pd(a), 1));
    for (; k + 8 <= stop; k += 8) eight_avx2(r, k, a0, a1);
    const __m256 h = _mm256_add_ps(a0, a1);
    const __m128 sum = _mm_add_ps(_mm256_castps256_ps128(h), _mm256_extractf128_ps(h, 1));
    store_row(tail_avx2(r, k, stop, sum), r.scale, out[row]);
  }
}
#pragma GCC diagnostic pop
#endif

}  // namespace

std::vector<CompactLoop> compact_loops() {
  std::vector<CompactLoop> loops{{"sse2", compact_band_sse2}};
#ifdef BOUNCE_AVX2_BLOCK_LOOP
  if (block_loops::cpu_has_avx2()) loops.push_back({"avx2", compact_band_avx2, true});
  if (block_loops::cpu_has_avx512()) loops.push_back({"avx512", compact_band_avx512, true});
#endif
  return loops;
}

CompactLoop compact_loop(const std::string& name) {
  for (const CompactLoop& loop : compact_loops())
    if (loop.name == name) return loop;
  throw Error("final gather", "this CPU has no gather loop '" + name + "'");
}

void sum_compact_rows(const CompactLoop& loop, const CompactRows& rows, std::size_t count,
                      glm::vec3* out, RowSlice slice) {
  // Bands of kRowBand rows: a few hundred kilobytes of entries each, enough
  // to hide the scheduling and few enough that both threads end together.
  const std::size_t all_bands = (count + kRowBand - 1) / kRowBand;
  const std::size_t step = slice.all() ? 1 : static_cast<std::size_t>(slice.slices);
  const std::size_t start = slice.all() ? 0 : static_cast<std::size_t>(slice.slice);
  const auto bands =
      static_cast<std::int64_t>(all_bands > start ? (all_bands - start + step - 1) / step : 0);
#pragma omp parallel for schedule(static, 1)
  for (std::int64_t b = 0; b < bands; ++b) {
    const std::size_t lo = (start + static_cast<std::size_t>(b) * step) * kRowBand;
    loop.sum(rows, lo, std::min(count, lo + kRowBand), out);
  }
}

}  // namespace bounce::gather_loops
