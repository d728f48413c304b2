#include "runtime/block_loops.h"

#include <array>

#ifdef BOUNCE_AVX2_BLOCK_LOOP
#include <immintrin.h>

#include "compress/bc1_palette_offsets.h"
#endif

namespace bounce::block_loops {

namespace {

template <DdsFormat kFormat, int kSlots>
void block_row_portable(const BlockRowInput& in, std::size_t I, float (*acc)[3]) {
  const Tables& t = in.t;
  const float* b = in.b;
  constexpr int kLevels = kFormat == DdsFormat::kBc1 ? 4 : 8;
  constexpr int kBits = kFormat == DdsFormat::kBc1 ? 2 : 3;
  const std::size_t nb = t.block_rows, padded = t.padded;
  const std::uint8_t* blocks = &t.blocks[I * nb * 8];
  for (std::size_t J = 0; J < nb; ++J) {
    // BC1: 2-bit indices in bytes 4..7; BC4: 3-bit indices in bytes 2..7.
    const std::uint64_t indices =
        kFormat == DdsFormat::kBc1 ? load_u32(blocks + 8 * J + 4) : load_u64(blocks + 8 * J) >> 16;
    const float* palette[3];
    for (std::size_t k = 0; k < 3; ++k)
      palette[k] = t.palette(I, J, kSlots == 1 ? 0 : t.slot_of_colour[k]);
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) {
        const auto e = static_cast<int>((indices >> (kBits * (4 * r + c))) & (kLevels - 1));
        for (std::size_t k = 0; k < 3; ++k)
          acc[r][k] += palette[k][e] * b[k * padded + 4 * J + static_cast<std::size_t>(c)];
      }
  }
}

#ifdef BOUNCE_AVX2_BLOCK_LOOP
// One block: the index word, shifted by a different amount in each of 8
// lanes, is the control of a permute of the palette, giving the values of
// rows r and r + 1 (4 texels each) in one register; a permute uses only the
// low 2 (BC1, in-lane vpermilps, palette in both lanes) or 3 (BC4, vpermps,
// 8-entry palette) bits of each lane, so no masking is needed. b of the
// block's 4 columns is broadcast to both lanes and multiplied in by FMA.
// The accumulators are named, not an array: GCC keeps arrays of them in
// memory and stores them every iteration.
template <DdsFormat kFormat>
__attribute__((target("avx2,fma"))) inline __m256 load_palette(const float* palette) {
  if constexpr (kFormat == DdsFormat::kBc1)
    return _mm256_broadcast_ps(reinterpret_cast<const __m128*>(palette));
  else
    return _mm256_loadu_ps(palette);
}

template <DdsFormat kFormat>
__attribute__((target("avx2,fma"))) inline __m256 permute(__m256 palette, __m256i control) {
  if constexpr (kFormat == DdsFormat::kBc1)
    return _mm256_permutevar_ps(palette, control);
  else
    return _mm256_permutevar8x32_ps(palette, control);
}

__attribute__((target("avx2,fma"))) inline void add_lanes(__m256 rows01, __m256 rows23,
                                                          float (*acc)[3], int k) {
  alignas(32) float lanes[2][8];
  _mm256_store_ps(lanes[0], rows01);
  _mm256_store_ps(lanes[1], rows23);
  for (int h = 0; h < 2; ++h)
    for (int r = 0; r < 2; ++r)
      acc[2 * h + r][k] +=
          (lanes[h][4 * r] + lanes[h][4 * r + 1]) + (lanes[h][4 * r + 2] + lanes[h][4 * r + 3]);
}

template <DdsFormat kFormat, int kSlots>
__attribute__((target("avx2,fma"))) void block_row_avx2(const BlockRowInput& in, std::size_t I,
                                                        float (*acc)[3]) {
  const Tables& t = in.t;
  const float* b = in.b;
  constexpr bool kBc1 = kFormat == DdsFormat::kBc1;
  constexpr std::size_t kLevels = kBc1 ? 4 : 8;
  const std::size_t nb = t.block_rows, padded = t.padded;
  const std::uint8_t* blocks = &t.blocks[I * nb * 8];
  // BC4: the block's own palette; BC1: the slot tables at the offsets the
  // endpoints give, 8 blocks at a time (colour k reads slot_of_colour[k]).
  const float* bc4_palettes = kBc1 ? nullptr : &t.palettes[I * nb * kLevels];
  const float* tables = t.bc1_tables.data();
  alignas(32) std::uint32_t offset[3][8] = {};
  const std::size_t slot_r = kSlots == 1 ? 0 : static_cast<std::size_t>(t.slot_of_colour[0]);
  const std::size_t slot_g = kSlots == 1 ? 0 : static_cast<std::size_t>(t.slot_of_colour[1]);
  const std::size_t slot_b = kSlots == 1 ? 0 : static_cast<std::size_t>(t.slot_of_colour[2]);
  const __m256i shift_lo = kBc1 ? _mm256_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14)
                                : _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  const __m256i shift_hi = kBc1 ? _mm256_setr_epi32(16, 18, 20, 22, 24, 26, 28, 30) : shift_lo;
  const float *b_r = b, *b_g = b + padded, *b_b = b + 2 * padded;
  // Rows 0 and 1 (resp. 2 and 3) x columns 0..3, per colour.
  __m256 r01 = _mm256_setzero_ps(), g01 = r01, b01 = r01, r23 = r01, g23 = r01, b23 = r01;
  for (std::size_t J = 0; J < nb; ++J) {
    const std::uint8_t* block = blocks + 8 * J;
    const std::size_t lane = J % 8;
    if constexpr (kBc1) {
      if (lane == 0) {
        bc1_offsets(t, block, std::min<std::size_t>(8, nb - J), offset);
      }
    }
    __m256i control01, control23;
    if constexpr (kBc1) {
      const __m256i word = _mm256_set1_epi32(static_cast<int>(load_u32(block + 4)));
      control01 = _mm256_srlv_epi32(word, shift_lo);
      control23 = _mm256_srlv_epi32(word, shift_hi);
    } else {
      const std::uint64_t field = load_u64(block) >> 16;  // 48 bits, 12 per row
      control01 =
          _mm256_srlv_epi32(_mm256_set1_epi32(static_cast<int>(field & 0xFFFFFF)), shift_lo);
      control23 = _mm256_srlv_epi32(_mm256_set1_epi32(static_cast<int>(field >> 24)), shift_lo);
    }
    const __m256 br = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(b_r + 4 * J));
    const __m256 bg = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(b_g + 4 * J));
    const __m256 bb = _mm256_broadcast_ps(reinterpret_cast<const __m128*>(b_b + 4 * J));
    if constexpr (kSlots == 1) {
      const __m256 p =
          load_palette<kFormat>(kBc1 ? tables + offset[0][lane] : bc4_palettes + J * kLevels);
      const __m256 v01 = permute<kFormat>(p, control01), v23 = permute<kFormat>(p, control23);
      r01 = _mm256_fmadd_ps(v01, br, r01);
      g01 = _mm256_fmadd_ps(v01, bg, g01);
      b01 = _mm256_fmadd_ps(v01, bb, b01);
      r23 = _mm256_fmadd_ps(v23, br, r23);
      g23 = _mm256_fmadd_ps(v23, bg, g23);
      b23 = _mm256_fmadd_ps(v23, bb, b23);
    } else {
      const __m256 pr = load_palette<kFormat>(tables + offset[slot_r][lane]);
      const __m256 pg = load_palette<kFormat>(tables + offset[slot_g][lane]);
      const __m256 pb = load_palette<kFormat>(tables + offset[slot_b][lane]);
      r01 = _mm256_fmadd_ps(permute<kFormat>(pr, control01), br, r01);
      g01 = _mm256_fmadd_ps(permute<kFormat>(pg, control01), bg, g01);
      b01 = _mm256_fmadd_ps(permute<kFormat>(pb, control01), bb, b01);
      r23 = _mm256_fmadd_ps(permute<kFormat>(pr, control23), br, r23);
      g23 = _mm256_fmadd_ps(permute<kFormat>(pg, control23), bg, g23);
      b23 = _mm256_fmadd_ps(permute<kFormat>(pb, control23), bb, b23);
    }
  }
  add_lanes(r01, r23, acc, 0);
  add_lanes(g01, g23, acc, 1);
  add_lanes(b01, b23, acc, 2);
}

// The values of one kept position as R, G, B, x. With 3 values per entry
// the 16-byte load reads the next entry's R (or the table's trailing 0) as
// x, which the 0 in b's fourth lane cancels.
template <int kWidth>
__attribute__((target("avx2,fma"))) inline __m128 load_value(const float* v) {
  if constexpr (kWidth == 3)
    return _mm_loadu_ps(v);
  else
    return _mm_broadcast_ss(v);
}

// The kept entries of block row I, row by row, one position per 4-float
// FMA, two positions per step on independent sums (the FMA latency would
// otherwise bound the loop).
template <int kWidth>
__attribute__((target("avx2,fma"))) void corrections_avx2(const Tables& t, const float* b4,
                                                          std::size_t I, float (*acc)[3]) {
  const std::uint32_t* index = t.correction_index.data();
  const float* value = t.correction_value.data();
  for (std::size_t r = 0; r < 4; ++r) {
    std::size_t e = t.correction_ptr[4 * I + r];
    const std::size_t end = t.correction_ptr[4 * I + r + 1];
    if (e == end) continue;
    __m128 s0 = _mm_setzero_ps(), s1 = s0;
    for (; e + 1 < end; e += 2) {
      const std::size_t j0 = index[e] & kCorrectionColumnMask;
      const std::size_t j1 = index[e + 1] & kCorrectionColumnMask;
      s0 = _mm_fmadd_ps(load_value<kWidth>(value + kWidth * e), _mm_loadu_ps(b4 + 4 * j0), s0);
      s1 =
          _mm_fmadd_ps(load_value<kWidth>(value + kWidth * (e + 1)), _mm_loadu_ps(b4 + 4 * j1), s1);
    }
    if (e < end)
      s0 = _mm_fmadd_ps(load_value<kWidth>(value + kWidth * e),
                        _mm_loadu_ps(b4 + 4 * (index[e] & kCorrectionColumnMask)), s0);
    alignas(16) float sum[4];
    _mm_store_ps(sum, _mm_add_ps(s0, s1));
    for (int k = 0; k < 3; ++k) acc[r][k] += sum[k];
  }
}

#endif

// A band of the loops that take one block row at a time.
template <BlockRowFn kRow>
void rows_one_by_one(const BlockRowInput& in, std::size_t I0, std::size_t rows, float (*acc)[3]) {
  for (std::size_t i = 0; i < rows; ++i) kRow(in, I0 + i, acc + 4 * i);
}

}  // namespace

BlockBandFn block_band_function(const Tables& t, bool avx2, bool avx512, bool bf16) {
  const bool bc1 = t.format == DdsFormat::kBc1;
#ifdef BOUNCE_AVX2_BLOCK_LOOP
  if (bf16 && bc1) return block_band_bf16;
  if (avx512 && bc1) return block_band_avx512;
  if (avx2) {
    if (!bc1) return rows_one_by_one<block_row_avx2<DdsFormat::kBc4, 1>>;
    return t.slots == 3 ? rows_one_by_one<block_row_avx2<DdsFormat::kBc1, 3>>
                        : rows_one_by_one<block_row_avx2<DdsFormat::kBc1, 1>>;
  }
#else
  (void)avx2;
  (void)avx512;
  (void)bf16;
#endif
  if (!bc1) return rows_one_by_one<block_row_portable<DdsFormat::kBc4, 1>>;
  return t.slots == 3 ? rows_one_by_one<block_row_portable<DdsFormat::kBc1, 3>>
                      : rows_one_by_one<block_row_portable<DdsFormat::kBc1, 1>>;
}

namespace {

// The kept entries of block row I, into the same accumulators as its blocks.
template <int kWidth>
void corrections_portable(const Tables& t, const float* b4, std::size_t I, float (*acc)[3]) {
  for (std::size_t r = 0; r < 4; ++r)
    for (std::uint32_t e = t.correction_ptr[4 * I + r]; e < t.correction_ptr[4 * I + r + 1]; ++e) {
      const float* v = &t.correction_value[kWidth * e];
      const float* x = b4 + 4 * (t.correction_index[e] & kCorrectionColumnMask);
      for (int k = 0; k < 3; ++k) acc[r][k] += v[kWidth == 3 ? k : 0] * x[k];
    }
}

}  // namespace

CorrectionsFn corrections_function(const Tables& t, bool avx2) {
#ifdef BOUNCE_AVX2_BLOCK_LOOP
  if (avx2) return t.correction_width == 3 ? corrections_avx2<3> : corrections_avx2<1>;
#else
  (void)avx2;
#endif
  return t.correction_width == 3 ? corrections_portable<3> : corrections_portable<1>;
}

}  // namespace bounce::block_loops
