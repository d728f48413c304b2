#include <algorithm>
#include <array>

#include "runtime/block_loops.h"

#ifdef BOUNCE_AVX2_BLOCK_LOOP
#include <immintrin.h>

namespace bounce::block_loops {

namespace {

// GCC 12's AVX-512 intrinsic headers start some results from
// _mm512_undefined_*(), which -Wmaybe-uninitialized reports at every use
// (GCC bug 105593, fixed in GCC 13); the warning is about the header.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
// AVX-512, BC1: the whole block in one 16-lane register per colour. The
// index word, shifted by 2t in lane t, is the control of an in-lane permute
// of the palette (broadcast to the four 128-bit lanes), giving texel t's
// value in lane t, row r in 128-bit lane r; b of the block's 4 columns is
// broadcast to the four lanes. Half the permutes and FMAs of the AVX2 loop
// (3 each per block), on 512-bit units where the CPU has them. Two sets of
// accumulators (even and odd blocks) hide the FMA latency.
__attribute__((target("avx512f"))) inline void add_rows(__m512 rows, float (*acc)[3], int k) {
  alignas(64) float lanes[16];
  _mm512_store_ps(lanes, rows);
  for (int r = 0; r < 4; ++r)
    acc[r][k] += (lanes[4 * r] + lanes[4 * r + 1]) + (lanes[4 * r + 2] + lanes[4 * r + 3]);
}

// The AVX-512 loops read a block row as Bc1BlockPair records (header):
// the index words of two neighbouring blocks and, per block and colour, the
// entry of its palette in the tables, laid out once when the object is
// built. Before, each product derived the entries from the endpoint words,
// ~30 scalar instructions per block (3 keys of shifts, masks and a compare)
// in a pass over the block row before its loop: 2.4 ms of the 11.5 ms
// float32 product at one thread on this machine (docs/benchmarks.md,
// `bounce bench runtime`).
//
// The palette at `units` of 8 bytes into `tables` (Bc1BlockPair::palette):
// one scaled-index address, no shift.
template <typename T>
inline const T* palette(const T* tables, std::uint16_t units) {
  return reinterpret_cast<const T*>(reinterpret_cast<const char*>(tables) + 8 * std::size_t{units});
}

template <bool kSecondBlock>
__attribute__((target("avx512f,avx2,fma"))) inline void bc1_block_avx512(
    const Bc1BlockPair& pair, const float* tables, const float* b_r, const float* b_g,
    const float* b_b, __m512i shift, __m512& ar, __m512& ag, __m512& ab) {
  constexpr int j = kSecondBlock ? 1 : 0;
  const __m512i control =
      _mm512_srlv_epi32(_mm512_set1_epi32(static_cast<int>(pair.indices[j])), shift);
  const __m512 pr = _mm512_broadcast_f32x4(_mm_loadu_ps(palette(tables, pair.palette[j][0])));
  const __m512 pg = _mm512_broadcast_f32x4(_mm_loadu_ps(palette(tables, pair.palette[j][1])));
  const __m512 pb = _mm512_broadcast_f32x4(_mm_loadu_ps(palette(tables, pair.palette[j][2])));
  ar = _mm512_fmadd_ps(_mm512_permutevar_ps(pr, control),
                       _mm512_broadcast_f32x4(_mm_loadu_ps(b_r + 4 * j)), ar);
  ag = _mm512_fmadd_ps(_mm512_permutevar_ps(pg, control),
                       _mm512_broadcast_f32x4(_mm_loadu_ps(b_g + 4 * j)), ag);
  ab = _mm512_fmadd_ps(_mm512_permutevar_ps(pb, control),
                       _mm512_broadcast_f32x4(_mm_loadu_ps(b_b + 4 * j)), ab);
}

// The AVX-512 loops run a band of kBandRows block rows a tile of b at a
// time: pairs [p0, p1) of every row of the band, then the next tile. Every
// block row reads all of b; row by row, that sweep (3 x 34 KB in float32,
// 3 x 17 KB in bfloat16) does not fit the 32 KB L1 next to the palette
// tables, so each row read b from L2 again. In tiles, the band's rows share
// a tile of b that stays in L1. The records are stored in this order
// (pair_record), else the loop reads 8 short streams of blocks and is slower
// than row by row. At one thread on this machine, bfloat16 7.3 -> 5.5 ms,
// float32 8.8 -> 8.2 ms (docs/benchmarks.md, `bounce bench runtime`). The row
// sums of the band wait in memory (3 registers per row) between tiles.
// kBandRows is above, with BlockBandFn.

// How far ahead the float32 loop prefetches its records: 2.5 KB, as the
// bfloat16 loop's kPrefetchGroups.
constexpr std::size_t kPrefetchPairs = 128;
// Pairs [p0, p1) of a block row (float32), whose records start at first,
// into sums (R, G, B).
__attribute__((target("avx512f,avx2,fma"))) inline void avx512_bc1_pairs(const BlockRowInput& in,
                                                                         const Bc1BlockPair* first,
                                                                         std::size_t p0,
                                                                         std::size_t p1,
                                                                         __m512* sums) {
  const std::size_t nb = in.t.block_rows, padded = in.t.padded;
  const float* tables = in.t.bc1_tables.data();
  const __m512i shift =
      _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
  const float *b_r = in.b, *b_g = in.b + padded, *b_b = in.b + 2 * padded;
  // Named accumulators, two sets (first and second block of a pair): GCC
  // keeps an array of them indexed by J & 1 on the stack, and the
  // store-to-load chain then bounds the loop.
  __m512 r0 = sums[0], g0 = sums[1], b0 = sums[2];
  __m512 r1 = _mm512_setzero_ps(), g1 = r1, b1 = r1;
  const std::size_t full_end = std::min(p1, nb / 2);
  for (std::size_t p = p0; p < full_end; ++p) {
    const std::size_t c = 8 * p;  // first stored column of the pair
    const Bc1BlockPair& pair = first[p - p0];
    // The record stream prefetched as in the bfloat16 loop (below), one line
    // ahead per 64 bytes of records.
    if ((p - p0) % 4 == 0)
      _mm_prefetch(reinterpret_cast<const char*>(reinterpret_cast<std::uintptr_t>(&pair) +
                                                 kPrefetchPairs * sizeof(Bc1BlockPair)),
                   _MM_HINT_NTA);
    bc1_block_avx512<false>(pair, tables, b_r + c, b_g + c, b_b + c, shift, r0, g0, b0);
    bc1_block_avx512<true>(pair, tables, b_r + c, b_g + c, b_b + c, shift, r1, g1, b1);
  }
  // An odd last block: its pair's second block is padding, and b has no
  // columns there (b_b's would be past the end of b).
  if (nb % 2 == 1 && p1 == in.pairs_per_row) {
    const std::size_t c = 8 * (nb / 2);
    bc1_block_avx512<false>(first[nb / 2 - p0], tables, b_r + c, b_g + c, b_b + c, shift, r0, g0,
                            b0);
  }
  sums[0] = _mm512_add_ps(r0, r1);
  sums[1] = _mm512_add_ps(g0, g1);
  sums[2] = _mm512_add_ps(b0, b1);
}

// AVX-512 with bfloat16 products (the default for BC1 where the CPU has
// AVX512_BF16 and VBMI): one row of 8 neighbouring blocks (32 texels, one
// Bc1BlockGroup) in one 32-lane register of 16-bit values per colour, rows
// 0-3 of the group in four registers. Per group:
// - the 8 index words, zero-extended to one qword per block, and per row r
//   vpmultishiftqb + vpternlogd turn them into the control of a vpermw:
//   word 4q + c is texel (r, c) of block q, its 2-bit index plus 4q, block
//   q's palette (words 4q .. 4q + 3 of the palette register);
// - per colour, the 8 blocks' palettes (8 bytes each, bfloat16 tables) into
//   one register, then per row vpermw reads the texels' values and
//   vdpbf16ps multiplies pairs of texels by b (bfloat16) and adds both
//   products into a float32 lane. b of the group's 32 columns is one
//   aligned 64-byte load, shared by the 4 rows (no broadcast).
// Row r's sum is the sum of its register's 16 lanes. Rounding: palettes and
// b to 8-bit mantissas (relative 2^-9 each), sums in float32.
//
// Why this layout (docs/benchmarks.md, `bounce bench runtime`): this CPU
// (Zen 5) runs 512-bit operations at full width but at most 2 vector loads
// per cycle; the earlier loop (two blocks per register) needed 10 vector
// loads per two blocks (index word, 6 palettes, 3 broadcasts of b), this
// one 7 (6 palettes, 1/4 index load, 3/4 b load). What bounded both more
// was the record stream itself (45 MB per product, more than the caches):
// the records are prefetched kPrefetchGroups ahead (2.5 KB; 16 to 64 groups
// were within noise of each other, 8 and 128 slower), non-temporal (they
// are read once; measured a few percent faster than into all levels).
constexpr std::size_t kPrefetchGroups = 32;
// vpmultishiftqb's selectors for row r: both bytes of word c of every qword
// take the 8 bits from bit 2 * (4r + c) of the block's index word.
alignas(64) constexpr std::array<std::array<std::uint8_t, 64>, 4> kRowSelect = [] {
  std::array<std::array<std::uint8_t, 64>, 4> select{};
  for (std::size_t r = 0; r < 4; ++r)
    for (std::size_t q = 0; q < 8; ++q)
      for (std::size_t c = 0; c < 4; ++c)
        select[r][8 * q + 2 * c] = select[r][8 * q + 2 * c + 1] =
            static_cast<std::uint8_t>(8 * r + 2 * c);
  return select;
}();
// Word m (block m / 4) reads its block's palette at words 4 (m / 4) ...
alignas(64) constexpr std::array<std::uint16_t, 32> kGroupPaletteBase = [] {
  std::array<std::uint16_t, 32> base{};
  for (std::size_t m = 0; m < 32; ++m) base[m] = static_cast<std::uint16_t>(m & ~std::size_t{3});
  return base;
}();

// Groups [g0, g1) of a block row, whose records start at first, into sums
// (row r, colour k at 3 r + k).
__attribute__((target("avx512f,avx512bw,avx512vl,avx512vbmi,avx512bf16,avx2,fma"))) inline void
avx512_bf16_groups(const BlockRowInput& in, const Bc1BlockGroup* first, std::size_t g0,
                   std::size_t g1, __m512* sums) {
  const __m512i select0 = _mm512_load_si512(kRowSelect[0].data());
  const __m512i select1 = _mm512_load_si512(kRowSelect[1].data());
  const __m512i select2 = _mm512_load_si512(kRowSelect[2].data());
  const __m512i select3 = _mm512_load_si512(kRowSelect[3].data());
  const __m512i low2 = _mm512_set1_epi16(3);
  const __m512i base = _mm512_load_si512(kGroupPaletteBase.data());
  const std::uint16_t* tables = in.tables16;
  const auto eight_palettes = [tables](const std::uint16_t* units)
      __attribute__((always_inline, target("avx512f,avx512bw,avx512vl,avx2"))) {
    const auto two = [ tables, units ](int j) __attribute__((always_inline, target("avx2"))) {
      return _mm_unpacklo_epi64(
          _mm_loadl_epi64(reinterpret_cast<const __m128i*>(palette(tables, units[j]))),
          _mm_loadl_epi64(reinterpret_cast<const __m128i*>(palette(tables, units[j + 1]))));
    };
    const __m256i lo = _mm256_inserti128_si256(_mm256_castsi128_si256(two(0)), two(2), 1);
    const __m256i hi = _mm256_inserti128_si256(_mm256_castsi128_si256(two(4)), two(6), 1);
    return _mm512_inserti64x4(_mm512_castsi256_si512(lo), hi, 1);
  };
  // Named accumulators (see avx512_bc1_pairs): row r, R / G / B.
  __m512 r0 = sums[0], g0s = sums[1], b0 = sums[2], r1 = sums[3], g1s = sums[4], b1 = sums[5];
  __m512 r2 = sums[6], g2s = sums[7], b2 = sums[8], r3 = sums[9], g3s = sums[10], b3 = sums[11];
  for (std::size_t g = g0; g < g1; ++g) {
    const Bc1BlockGroup& group = first[g - g0];
    // As an integer: the address may be past the end of the records (a
    // prefetch does not fault), which pointer arithmetic may not be.
    _mm_prefetch(reinterpret_cast<const char*>(reinterpret_cast<std::uintptr_t>(&group) +
                                               kPrefetchGroups * sizeof(Bc1BlockGroup)),
                 _MM_HINT_NTA);
    const __m512i words =
        _mm512_cvtepu32_epi64(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(group.indices)));
    // (index & 3) | 4 * block.
    const __m512i c0 =
        _mm512_ternarylogic_epi32(_mm512_multishift_epi64_epi8(select0, words), low2, base, 0xEA);
    const __m512i c1 =
        _mm512_ternarylogic_epi32(_mm512_multishift_epi64_epi8(select1, words), low2, base, 0xEA);
    const __m512i c2 =
        _mm512_ternarylogic_epi32(_mm512_multishift_epi64_epi8(select2, words), low2, base, 0xEA);
    const __m512i c3 =
        _mm512_ternarylogic_epi32(_mm512_multishift_epi64_epi8(select3, words), low2, base, 0xEA);
    const auto colour = [&](std::size_t k, __m512 & a0, __m512 & a1, __m512 & a2, __m512 & a3)
        __attribute__((always_inline,
                       target("avx512f,avx512bw,avx512vl,avx512vbmi,avx512bf16,avx2,fma"))) {
      const __m512i values = eight_palettes(group.palette[k]);
      const auto b =
          reinterpret_cast<__m512bh>(_mm512_load_si512(in.b16 + k * in.b16_stride + 32 * g));
      a0 =
          _mm512_dpbf16_ps(a0, reinterpret_cast<__m512bh>(_mm512_permutexvar_epi16(c0, values)), b);
      a1 =
          _mm512_dpbf16_ps(a1, reinterpret_cast<__m512bh>(_mm512_permutexvar_epi16(c1, values)), b);
      a2 =
          _mm512_dpbf16_ps(a2, reinterpret_cast<__m512bh>(_mm512_permutexvar_epi16(c2, values)), b);
      a3 =
          _mm512_dpbf16_ps(a3, reinterpret_cast<__m512bh>(_mm512_permutexvar_epi16(c3, values)), b);
    };
    colour(0, r0, r1, r2, r3);
    colour(1, g0s, g1s, g2s, g3s);
    colour(2, b0, b1, b2, b3);
  }
  sums[0] = r0, sums[1] = g0s, sums[2] = b0, sums[3] = r1, sums[4] = g1s, sums[5] = b1;
  sums[6] = r2, sums[7] = g2s, sums[8] = b2, sums[9] = r3, sums[10] = g3s, sums[11] = b3;
}

}  // namespace

// The bfloat16 loop over a band: as block_band_avx512 below, tiles of
// kTileGroups groups, then each row's 12 sums reduced.
__attribute__((target("avx512f,avx512bw,avx512vl,avx512vbmi,avx512bf16,avx2,fma"))) void
block_band_bf16(const BlockRowInput& in, std::size_t I0, std::size_t rows, float (*acc)[3]) {
  __m512 sums[kBandRows][12];
  for (std::size_t i = 0; i < rows; ++i)
    for (__m512& s : sums[i]) s = _mm512_setzero_ps();
  const std::size_t count = in.groups_per_row;
  for (std::size_t g0 = 0; g0 < count; g0 += kTileGroups) {
    const std::size_t g1 = std::min(g0 + kTileGroups, count);
    for (std::size_t i = 0; i < rows; ++i)
      avx512_bf16_groups(in, in.groups + group_record(in.t.block_rows, count, I0 + i, g0), g0, g1,
                         sums[i]);
  }
  for (std::size_t i = 0; i < rows; ++i)
    for (std::size_t r = 0; r < 4; ++r)
      for (std::size_t k = 0; k < 3; ++k)
        acc[4 * i + r][k] += _mm512_reduce_add_ps(sums[i][3 * r + k]);
}

// Block rows I0 .. I0 + rows - 1 (rows <= kBandRows) into acc[4 * i + r]
// (block row I0 + i, row r), tile by tile; kTilePairs pairs per tile, 12 KB
// of b.
__attribute__((target("avx512f,avx2,fma"))) void block_band_avx512(const BlockRowInput& in,
                                                                   std::size_t I0, std::size_t rows,
                                                                   float (*acc)[3]) {
  __m512 sums[kBandRows][3];
  for (std::size_t i = 0; i < rows; ++i)
    for (__m512& s : sums[i]) s = _mm512_setzero_ps();
  const std::size_t count = in.pairs_per_row;
  for (std::size_t p0 = 0; p0 < count; p0 += kTilePairs) {
    const std::size_t p1 = std::min(p0 + kTilePairs, count);
    for (std::size_t i = 0; i < rows; ++i) {
      const Bc1BlockPair* first = in.pairs + pair_record(in.t.block_rows, count, I0 + i, p0);
      avx512_bc1_pairs(in, first, p0, p1, sums[i]);
    }
  }
  for (std::size_t i = 0; i < rows; ++i)
    for (int k = 0; k < 3; ++k) add_rows(sums[i][k], acc + 4 * i, k);
}
#pragma GCC diagnostic pop

}  // namespace bounce::block_loops

#endif  // BOUNCE_AVX2_BLOCK_LOOP
