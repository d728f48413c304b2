#pragma once
// The loops that sum the final gather's rows (runtime/final_gather.h), one
// per instruction set. Internal to the runtime: final_gather_product.cpp runs
// them, and FinalGather::compact_rows() picks the loop the product runs by
// timing each on the rows it is given.
//
// A row is a list of entries (a source, a weight); its sum is
// sum_k weight_k * light[source_k], each source's light padded to four
// floats so that one 16-byte load fetches its colour.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "runtime/gather_row_budget.h"

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace bounce::gather_loops {

// A source's light, padded to 16 bytes.
struct alignas(16) PaddedLight {
  float c[4] = {0.0f, 0.0f, 0.0f, 0.0f};
};

// sum_k term(k) over one row's entries [begin, end), times `scale`, where
// term(k) is entry k's weight times its source's padded light.
#if defined(__SSE2__)
template <typename Term>
glm::vec3 sum_row(Term term, std::uint64_t begin, std::uint64_t end, float scale) {
  // Two sums, so that consecutive entries do not wait on each other's add.
  __m128 e0 = _mm_setzero_ps(), e1 = _mm_setzero_ps();
  std::uint64_t k = begin;
  for (; k + 2 <= end; k += 2) {
    e0 = _mm_add_ps(e0, _mm_mul_ps(_mm_set1_ps(term.weight(k)), _mm_load_ps(term.light(k))));
    e1 =
        _mm_add_ps(e1, _mm_mul_ps(_mm_set1_ps(term.weight(k + 1)), _mm_load_ps(term.light(k + 1))));
  }
  if (k < end)
    e0 = _mm_add_ps(e0, _mm_mul_ps(_mm_set1_ps(term.weight(k)), _mm_load_ps(term.light(k))));
  alignas(16) float e[4];
  _mm_store_ps(e, _mm_mul_ps(_mm_set1_ps(scale), _mm_add_ps(e0, e1)));
  return glm::vec3(e[0], e[1], e[2]);
}
#else
template <typename Term>
glm::vec3 sum_row(Term term, std::uint64_t begin, std::uint64_t end, float scale) {
  glm::vec3 e(0.0f);
  for (std::uint64_t k = begin; k < end; ++k) {
    const float* l = term.light(k);
    e += term.weight(k) * glm::vec3(l[0], l[1], l[2]);
  }
  return scale * e;
}
#endif

// Float rows: a source index and a weight per entry.
struct FloatEntries {
  const PaddedLight* light_of;
  const std::uint32_t* source;
  const float* weights;
  float weight(std::uint64_t k) const { return weights[k]; }
  const float* light(std::uint64_t k) const { return light_of[source[k]].c; }
};

// Compact rows: the ray count in the low bits, the source above them.
struct CompactEntries {
  const PaddedLight* light_of;
  const std::uint32_t* entry;
  int count_bits;
  std::uint32_t count_mask;
  float weight(std::uint64_t k) const { return static_cast<float>(entry[k] & count_mask); }
  const float* light(std::uint64_t k) const { return light_of[entry[k] >> count_bits].c; }
};

// The compact rows (FinalGather::compact): entry k holds a ray count in its
// low `count_bits` bits and the source above them; a row's sum of counts
// times light is multiplied by `scale` (1 / the rays per point) once.
struct CompactRows {
  const PaddedLight* light = nullptr;
  const std::uint64_t* first = nullptr;  // rows + 1 offsets into `entry`
  const std::uint32_t* entry = nullptr;
  int count_bits = 0;
  float scale = 1.0f;
};

// Sums rows [begin, end) into out[begin .. end).
using CompactBandFn = void (*)(const CompactRows&, std::size_t begin, std::size_t end,
                               glm::vec3* out);

struct CompactLoop {
  std::string name;
  CompactBandFn sum = nullptr;
  // The fused loops ("avx2", "avx512") give the same sums to the bit.
  bool fused = false;
};

// The loops this CPU runs, the portable one first: "sse2" decodes and adds
// one entry at a time; "avx2" decodes eight entries at once and adds two per
// fused multiply-add; "avx512" decodes sixteen and adds four per fused
// multiply-add. The wider loops round each multiply-add once instead of
// twice, so their sums differ from the portable one's in the last bits; the
// two wide loops add every entry in the same order, so they agree to the bit.
std::vector<CompactLoop> compact_loops();
// The loop named `name`; throws bounce::Error when this CPU has none by that
// name.
CompactLoop compact_loop(const std::string& name);

// Sums the rows of `rows` (`count` rows) that `slice` takes, in bands of
// kRowBand, with `loop` on the threads; the others in `out` are left as
// they are.
void sum_compact_rows(const CompactLoop& loop, const CompactRows& rows, std::size_t count,
                      glm::vec3* out, RowSlice slice = {});

}  // namespace bounce::gather_loops
