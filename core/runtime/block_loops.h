#pragma once
// The block loops of the CPU product (runtime/compressed_transport.h), one
// per instruction set: what CompressedTransport::multiply runs on a band of
// block rows, and the pass that adds the kept entries' corrections. Internal
// to the runtime; block_loops.cpp holds the portable and AVX2 loops and the
// choice between loops, block_loops_avx512.cpp the two AVX-512 loops (float32
// on Bc1BlockPair records, bfloat16 on Bc1BlockGroup records).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "compress/compressed_transport_tables.h"
#include "runtime/compressed_transport.h"

#if defined(__x86_64__) || defined(__i386__)
#define BOUNCE_AVX2_BLOCK_LOOP 1
#endif

namespace bounce::block_loops {

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
inline std::size_t loop_order(std::size_t nb, std::size_t per_row, std::size_t tile, std::size_t I,
                              std::size_t p) {
  const std::size_t I0 = I / kBandRows * kBandRows, rows = std::min(kBandRows, nb - I0);
  const std::size_t p0 = p / tile * tile, count = std::min(tile, per_row - p0);
  return I0 * per_row + p0 * rows + (I - I0) * count + (p - p0);
}
inline std::size_t pair_record(std::size_t nb, std::size_t pairs_per_row, std::size_t I,
                               std::size_t p) {
  return loop_order(nb, pairs_per_row, kTilePairs, I, p);
}
inline std::size_t group_record(std::size_t nb, std::size_t groups_per_row, std::size_t I,
                                std::size_t g) {
  return loop_order(nb, groups_per_row, kTileGroups, I, g);
}
using BlockBandFn = void (*)(const BlockRowInput&, std::size_t, std::size_t, float (*)[3]);
// Adds the kept entries' corrections of block row I (b: 4 floats per stored
// column, R, G, B, 0) to the same accumulators.
using CorrectionsFn = void (*)(const Tables&, const float*, std::size_t, float (*)[3]);

// Blocks are little-endian (DDS); they are read as integers in place.
static_assert(std::endian::native == std::endian::little, "block decoding assumes little-endian");

inline std::uint32_t load_u32(const std::uint8_t* p) {
  std::uint32_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}
inline std::uint64_t load_u64(const std::uint8_t* p) {
  std::uint64_t v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

// Whether this CPU runs the AVX2 (+ FMA), AVX-512 (F) and bfloat16 (AVX-512
// BF16 + BW + VL + VBMI) loops; false off x86.
bool cpu_has_avx2();
bool cpu_has_avx512();
bool cpu_has_avx512_bf16();

// The loop for a band of block rows: the bfloat16 loop if `bf16`, else the
// fastest of AVX-512 / AVX2 / portable allowed and fitting the format.
BlockBandFn block_band_function(const Tables& t, bool avx2, bool avx512, bool bf16);
// The corrections pass (AVX2 if allowed, else portable).
CorrectionsFn corrections_function(const Tables& t, bool avx2);

#ifdef BOUNCE_AVX2_BLOCK_LOOP
// block_loops_avx512.cpp; BC1 only, on the CPUs cpu_has_avx512() /
// cpu_has_avx512_bf16() accept.
void block_band_avx512(const BlockRowInput& in, std::size_t I0, std::size_t rows, float (*acc)[3]);
void block_band_bf16(const BlockRowInput& in, std::size_t I0, std::size_t rows, float (*acc)[3]);
#endif

}  // namespace bounce::block_loops
