#include "runtime/compressed_transport.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "base/error.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define BOUNCE_AVX2_BLOCK_LOOP 1
#endif

namespace bounce {

namespace {

using Tables = CompressedTransportTables;
// What a block loop reads besides the tables: b in stored order, colour-major
// (float32), or for the bfloat16 loop the same b and the BC1 palette tables
// rounded to bfloat16 (b16_stride entries per colour, zero past n).
struct BlockRowInput {
  const Tables& t;
  const float* b;
  const std::uint16_t* b16 = nullptr;
  std::size_t b16_stride = 0;
  const std::uint16_t* tables16 = nullptr;
  // The float32 AVX-512 loop (BC1): pairs_per_row records per block row.
  const Bc1BlockPair* pairs = nullptr;
  std::size_t pairs_per_row = 0;
  // The bfloat16 loop (BC1): groups_per_row records per block row.
  const Bc1BlockGroup* groups = nullptr;
  std::size_t groups_per_row = 0;
};
// Accumulates block row I of T~ times b into acc[row within the block
// row][colour].
using BlockRowFn = void (*)(const BlockRowInput&, std::size_t, float (*)[3]);
// Accumulates block rows I0 .. I0 + rows - 1 (rows <= kBandRows) into
// acc[4 * i + r] (block row I0 + i, row r). The product runs bands of
// block rows on the threads (the AVX-512 loops tile b over a band, below).
constexpr std::size_t kBandRows = 8;
// Pairs of a tile of b: 128 (1024 stored columns; 6 KB of b in bfloat16,
// 12 KB in float32) was faster than 64 and 256 on this machine.
constexpr std::size_t kTilePairs = 128;
// The bfloat16 loop's tile: the same 1024 stored columns, 32 groups of 8
// blocks.
constexpr std::size_t kTileGroups = kTilePairs / 4;
// Where record p (per_row records per block row, `tile` per tile) of block
// row I is: in the order the AVX-512 loops read them, band by band, tile by
// tile, and in a tile row by row, so that the loops read one sequential
// stream.
std::size_t loop_order(std::size_t nb, std::size_t per_row, std::size_t tile, std::size_t I,
                       std::size_t p) {
  const std::size_t I0 = I / kBandRows * kBandRows, rows = std::min(kBandRows, nb - I0);
  const std::size_t p0 = p / tile * tile, count = std::min(tile, per_row - p0);
  return I0 * per_row + p0 * rows + (I - I0) * count + (p - p0);
}
std::size_t pair_record(std::size_t nb, std::size_t pairs_per_row, std::size_t I, std::size_t p) {
  return loop_order(nb, pairs_per_row, kTilePairs, I, p);
}
std::size_t group_record(std::size_t nb, std::size_t groups_per_row, std::size_t I, std::size_t g) {
  return loop_order(nb, groups_per_row, kTileGroups, I, g);
}
using BlockBandFn = void (*)(const BlockRowInput&, std::size_t, std::size_t, float (*)[3]);
// Adds the kept entries' corrections of block row I (b: 4 floats per stored
// column, R, G, B, 0) to the same accumulators.
using CorrectionsFn = void (*)(const Tables&, const float*, std::size_t, float (*)[3]);

// Blocks are little-endian (DDS); they are read as integers in place.
static_assert(std::endian::native == std::endian::little, "block decoding assumes little-endian");

std::uint32_t load_u32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
std::uint64_t load_u64(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

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

// The palette-table offsets (floats into bc1_tables) of 8 consecutive BC1
// blocks, per slot: bc1_palette_key of each block's endpoints, 8 at once.
// Scalar, the key costs ~10 integer instructions per slot, as much as the
// rest of the block; in vectors, ~2 per block for all three slots.
__attribute__((target("avx2,fma"))) inline void bc1_offsets_x8(const Tables& t,
                                                               const std::uint8_t* blocks,
                                                               std::uint32_t (*offset)[8]) {
  static_assert(Tables::bc1_field_shift == std::array<std::uint32_t, 3>{11, 5, 0} &&
                Tables::bc1_field_bits == std::array<std::uint32_t, 3>{5, 6, 5});
  // Endpoint words are the even dwords of the 8 blocks: the shuffle takes
  // them in the order 0 1 4 5 | 2 3 6 7, the 64-bit permute restores 0..7.
  const __m256 lo = _mm256_loadu_ps(reinterpret_cast<const float*>(blocks));
  const __m256 hi = _mm256_loadu_ps(reinterpret_cast<const float*>(blocks + 32));
  const __m256i endpoints = _mm256_permute4x64_epi64(
      _mm256_castps_si256(_mm256_shuffle_ps(lo, hi, _MM_SHUFFLE(2, 0, 2, 0))),
      _MM_SHUFFLE(3, 1, 2, 0));
  const __m256i c0 = _mm256_and_si256(endpoints, _mm256_set1_epi32(0xFFFF));
  const __m256i c1 = _mm256_srli_epi32(endpoints, 16);
  // 1 in the 3-colour mode (colour0 <= colour1): -1 + 1 when c0 > c1 is 0.
  const __m256i mode = _mm256_add_epi32(_mm256_cmpgt_epi32(c0, c1), _mm256_set1_epi32(1));
  const __m256i m5 = _mm256_set1_epi32(31), m6 = _mm256_set1_epi32(63);
  const __m256i key_r = _mm256_or_si256(
      _mm256_slli_epi32(mode, 10),
      _mm256_or_si256(_mm256_slli_epi32(_mm256_srli_epi32(c0, 11), 5), _mm256_srli_epi32(c1, 11)));
  const __m256i key_g = _mm256_or_si256(
      _mm256_slli_epi32(mode, 12),
      _mm256_or_si256(_mm256_slli_epi32(_mm256_and_si256(_mm256_srli_epi32(c0, 5), m6), 6),
                      _mm256_and_si256(_mm256_srli_epi32(c1, 5), m6)));
  const __m256i key_b = _mm256_or_si256(
      _mm256_slli_epi32(mode, 10),
      _mm256_or_si256(_mm256_slli_epi32(_mm256_and_si256(c0, m5), 5), _mm256_and_si256(c1, m5)));
  const __m256i keys[3] = {key_r, key_g, key_b};
  for (int s = 0; s < t.slots; ++s)
    _mm256_store_si256(
        reinterpret_cast<__m256i*>(offset[s]),
        _mm256_add_epi32(
            _mm256_slli_epi32(keys[s], 2),
            _mm256_set1_epi32(static_cast<int>(t.bc1_table_offset[static_cast<std::size_t>(s)]))));
}

// The offsets of the next `count` (1..8) blocks: 8 at once in vectors, or
// one by one at the end of a block row.
__attribute__((target("avx2,fma"))) inline void bc1_offsets(const Tables& t,
                                                            const std::uint8_t* blocks,
                                                            std::size_t count,
                                                            std::uint32_t (*offset)[8]) {
  if (count == 8) return bc1_offsets_x8(t, blocks, offset);
  for (std::size_t j = 0; j < count; ++j)
    for (std::size_t s = 0; s < static_cast<std::size_t>(t.slots); ++s)
      offset[s][j] = static_cast<std::uint32_t>(
          t.bc1_table_offset[s] +
          4 * bc1_palette_key(load_u32(blocks + 8 * j), t.bc1_field_shift[s], t.bc1_field_bits[s]));
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

bool cpu_has_avx2() { return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"); }

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
// runtime, session 6).
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
// float32 8.8 -> 8.2 ms (docs/benchmarks.md, runtime, session 6). The row
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
// Why this layout (docs/benchmarks.md, runtime, session 7): this CPU
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

bool cpu_has_avx512() { return __builtin_cpu_supports("avx512f") && cpu_has_avx2(); }
bool cpu_has_avx512_bf16() {
  return cpu_has_avx512() && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512vbmi") &&
         __builtin_cpu_supports("avx512bf16");
}

#else
bool cpu_has_avx2() { return false; }
bool cpu_has_avx512() { return false; }
bool cpu_has_avx512_bf16() { return false; }
#endif

// A band of the loops that take one block row at a time.
template <BlockRowFn kRow>
void rows_one_by_one(const BlockRowInput& in, std::size_t I0, std::size_t rows, float (*acc)[3]) {
  for (std::size_t i = 0; i < rows; ++i) kRow(in, I0 + i, acc + 4 * i);
}

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

CorrectionsFn corrections_function(const Tables& t, bool avx2) {
#ifdef BOUNCE_AVX2_BLOCK_LOOP
  if (avx2) return t.correction_width == 3 ? corrections_avx2<3> : corrections_avx2<1>;
#else
  (void)avx2;
#endif
  return t.correction_width == 3 ? corrections_portable<3> : corrections_portable<1>;
}

}  // namespace

std::uint16_t to_bfloat16(float x) {
  // Round to nearest, ties to even, on the bit pattern: adding 0x7FFF plus
  // the lowest kept bit carries into the kept half exactly when the dropped
  // half is above one half ulp, or equal to it with an odd kept half.
  std::uint32_t u = std::bit_cast<std::uint32_t>(x);
  u += 0x7FFFu + ((u >> 16) & 1u);
  return static_cast<std::uint16_t>(u >> 16);
}

float from_bfloat16(std::uint16_t h) {
  return std::bit_cast<float>(static_cast<std::uint32_t>(h) << 16);
}

CompressedTransport::CompressedTransport(const CompressedMatrix& m,
                                         const std::array<int, 3>& channel_of_rgb, BlockLoop loop)
    : CompressedTransport(build_compressed_transport_tables(m, channel_of_rgb), loop) {}

CompressedTransport::CompressedTransport(CompressedTransportTables tables, BlockLoop loop)
    : tables_(std::move(tables)),
      avx2_((loop == BlockLoop::kFastest || loop == BlockLoop::kFloat32 ||
             loop == BlockLoop::kAvx2) &&
            cpu_has_avx2()),
      avx512_((loop == BlockLoop::kFastest || loop == BlockLoop::kFloat32) && cpu_has_avx512()),
      bf16_(loop == BlockLoop::kFastest && tables_.format == DdsFormat::kBc1 &&
            cpu_has_avx512_bf16()),
      b_quad_(4 * tables_.padded, 0.0f),
      y_stored_(3 * tables_.padded, 0.0f) {
  if (bf16_)
    lay_out_block_groups();
  else {
    b_stored_.assign(3 * tables_.padded, 0.0f);
    if (avx512_ && tables_.format == DdsFormat::kBc1) lay_out_block_pairs();
  }
}

namespace {
// Colour k's palette of a BC1 block with these endpoints, in units of 8
// bytes into the tables: `units_per_palette` is 1 for the bfloat16 tables,
// 2 for the float32 ones. Below 2^16, as the three tables hold
// 2 * (2^10 + 2^12 + 2^10) palettes.
std::uint16_t palette_units(const Tables& t, std::uint32_t endpoints, std::size_t k,
                            std::size_t units_per_palette) {
  static_assert(2 * 2 * ((1u << 10) + (1u << 12) + (1u << 10)) <= 0x10000u);
  const auto s = static_cast<std::size_t>(t.slot_of_colour[k]);
  return static_cast<std::uint16_t>(
      units_per_palette * (t.bc1_table_offset[s] / 4 +
                           bc1_palette_key(endpoints, t.bc1_field_shift[s], t.bc1_field_bits[s])));
}
}  // namespace

void CompressedTransport::lay_out_block_pairs() {
  const Tables& t = tables_;
  const std::size_t nb = t.block_rows;
  pairs_per_row_ = (nb + 1) / 2;
  block_pairs_.assign(nb * pairs_per_row_, Bc1BlockPair{});
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t row = 0; row < static_cast<std::ptrdiff_t>(nb); ++row) {
    const auto I = static_cast<std::size_t>(row);
    for (std::size_t J = 0; J < nb; ++J) {
      const std::uint8_t* block = &t.blocks[(I * nb + J) * 8];
      Bc1BlockPair& pair = block_pairs_[pair_record(nb, pairs_per_row_, I, J / 2)];
      const std::uint32_t endpoints = load_u32(block);
      pair.indices[J % 2] = load_u32(block + 4);
      for (std::size_t k = 0; k < 3; ++k)
        pair.palette[J % 2][k] = palette_units(t, endpoints, k, 2);
      // An odd last block's partner: zero indices into the same palettes.
      if (J + 1 == nb && J % 2 == 0)
        for (std::size_t k = 0; k < 3; ++k) pair.palette[1][k] = pair.palette[0][k];
    }
  }
}

void CompressedTransport::lay_out_block_groups() {
  const Tables& t = tables_;
  const std::size_t nb = t.block_rows;
  groups_per_row_ = (nb + 7) / 8;
  block_groups_.assign(nb * groups_per_row_, Bc1BlockGroup{});
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t row = 0; row < static_cast<std::ptrdiff_t>(nb); ++row) {
    const auto I = static_cast<std::size_t>(row);
    for (std::size_t G = 0; G < groups_per_row_; ++G) {
      Bc1BlockGroup& group = block_groups_[group_record(nb, groups_per_row_, I, G)];
      for (std::size_t j = 0; j < 8; ++j) {
        // Padding past the last block: zero indices, the last block's
        // palettes (finite values), zero b.
        const std::size_t J = std::min(8 * G + j, nb - 1);
        const std::uint8_t* block = &t.blocks[(I * nb + J) * 8];
        group.indices[j] = 8 * G + j < nb ? load_u32(block + 4) : 0;
        for (std::size_t k = 0; k < 3; ++k)
          group.palette[k][j] = palette_units(t, load_u32(block), k, 1);
      }
    }
  }
  bc1_tables16_.resize(t.bc1_tables.size());
  for (std::size_t i = 0; i < bc1_tables16_.size(); ++i)
    bc1_tables16_[i] = to_bfloat16(t.bc1_tables[i]);
  // 32 columns per group and colour, 32 entries of slack to start at a
  // 64-byte boundary.
  b16_.assign(3 * 32 * groups_per_row_ + 32, 0);
  const auto address = reinterpret_cast<std::uintptr_t>(b16_.data());
  b16_start_ = (64 - address % 64) % 64 / sizeof(std::uint16_t);
}

bool CompressedTransport::has_bf16_loop() { return cpu_has_avx512_bf16(); }

const char* CompressedTransport::block_loop() const {
  if (bf16_) return "avx512-bf16";
  if (avx512_ && tables_.format == DdsFormat::kBc1) return "avx512";
  return avx2_ ? "avx2" : "portable";
}

std::size_t CompressedTransport::bytes_per_product() const {
  const std::size_t b = tables_.n * sizeof(glm::vec3);
  // The AVX-512 loops read their records instead of the blocks, and the
  // bfloat16 loop its half-size copy of the palette tables.
  if (bf16_)
    return tables_.bytes() - tables_.blocks.size() - tables_.bc1_tables.size() * sizeof(float) +
           block_groups_.size() * sizeof(Bc1BlockGroup) +
           bc1_tables16_.size() * sizeof(std::uint16_t) + b;
  if (!block_pairs_.empty())
    return tables_.bytes() - tables_.blocks.size() + block_pairs_.size() * sizeof(Bc1BlockPair) + b;
  return tables_.bytes() + b;
}

void CompressedTransport::multiply(const std::vector<glm::vec3>& b,
                                   std::vector<glm::vec3>& indirect) const {
  if (b.size() == tables_.n && indirect.size() != tables_.n) indirect.resize(tables_.n);
  multiply(std::span<const glm::vec3>(b), std::span<glm::vec3>(indirect));
}

void CompressedTransport::multiply(std::span<const glm::vec3> b,
                                   std::span<glm::vec3> indirect) const {
  const Tables& t = tables_;
  if (b.size() != t.n)
    throw Error("compressed transport", "b has " + std::to_string(b.size()) + " entries for " +
                                            std::to_string(t.n) + " patches");
  if (indirect.size() != t.n)
    throw Error("compressed transport", "the output has " + std::to_string(indirect.size()) +
                                            " entries for " + std::to_string(t.n) + " patches");
  // One parallel region, three passes: gather b into stored order (4 floats
  // per column for the corrections, colour-major for the block loop, in
  // float32 or rounded to bfloat16; padding columns stay 0 from
  // construction); the block loop over bands of block rows into y_stored_;
  // the corrections and the scatter back to patch order. Block rows write
  // disjoint stored rows and patches (the permutation is a bijection).
  float* bs = b_stored_.data();
  float* b4 = b_quad_.data();
  std::uint16_t* b16 = bf16_ ? b16_.data() + b16_start_ : nullptr;
  const std::size_t padded = t.padded, b16_stride = 32 * groups_per_row_;
  float(*y)[3] = reinterpret_cast<float(*)[3]>(y_stored_.data());
  const BlockRowInput input{t,
                            bs,
                            b16,
                            b16_stride,
                            bc1_tables16_.data(),
                            block_pairs_.data(),
                            pairs_per_row_,
                            block_groups_.data(),
                            groups_per_row_};
  const BlockBandFn block_band = block_band_function(t, avx2_, avx512_, bf16_);
  const CorrectionsFn corrections = corrections_function(t, avx2_);
  glm::vec3* out = indirect.data();
  const auto n = static_cast<std::ptrdiff_t>(t.n);
  const auto block_rows = static_cast<std::ptrdiff_t>(t.block_rows);
  const auto bands = static_cast<std::ptrdiff_t>((t.block_rows + kBandRows - 1) / kBandRows);
#pragma omp parallel
  {
#pragma omp for schedule(static)
    for (std::ptrdiff_t si = 0; si < n; ++si) {
      const auto i = static_cast<std::size_t>(si);
      const glm::vec3& v = b[t.permutation[i]];
      b4[4 * i] = v.x;
      b4[4 * i + 1] = v.y;
      b4[4 * i + 2] = v.z;
      if (b16) {
        b16[i] = to_bfloat16(v.x);
        b16[b16_stride + i] = to_bfloat16(v.y);
        b16[2 * b16_stride + i] = to_bfloat16(v.z);
      } else {
        bs[i] = v.x;
        bs[padded + i] = v.y;
        bs[2 * padded + i] = v.z;
      }
    }
    // Dynamic chunks: on a shared machine one core may be busy elsewhere,
    // and a static split would wait for its half.
#pragma omp for schedule(dynamic, 1)
    for (std::ptrdiff_t band = 0; band < bands; ++band) {
      const std::size_t I0 = static_cast<std::size_t>(band) * kBandRows;
      const std::size_t rows = std::min(kBandRows, t.block_rows - I0);
      float acc[4 * kBandRows][3] = {};
      block_band(input, I0, rows, acc);
      std::memcpy(y + 4 * I0, acc, sizeof(float) * 3 * 4 * rows);
    }
#pragma omp for schedule(static)
    for (std::ptrdiff_t row = 0; row < block_rows; ++row) {
      const auto I = static_cast<std::size_t>(row);
      corrections(t, b4, I, y + 4 * I);
      for (std::size_t r = 0; r < 4 && 4 * I + r < t.n; ++r)
        out[t.permutation[4 * I + r]] =
            glm::vec3(y[4 * I + r][0], y[4 * I + r][1], y[4 * I + r][2]);
    }
  }
}

}  // namespace bounce
