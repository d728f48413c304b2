#pragma once
// Where the BC1 blocks' palettes are in the palette tables of
// compress/compressed_transport_tables.h, computed for 8 consecutive blocks at
// once. Scalar, bc1_palette_key costs ~10 integer instructions per slot, as
// much as the rest of a block's work in a product loop; in AVX2 vectors,
// about 2 per block for all three slots. Shared by the run-time product
// (block rows) and temporal radiosity (block columns stored column by
// column), both of which read blocks 8 bytes apart.
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "compress/compressed_transport_tables.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

namespace bounce {

// The palette-table offsets (floats into bc1_tables) of the 8 BC1 blocks at
// `blocks` (8 bytes apart), per slot: offset[s][j] for block j.
__attribute__((target("avx2,fma"))) inline void bc1_offsets_x8(const CompressedTransportTables& t,
                                                               const std::uint8_t* blocks,
                                                               std::uint32_t (*offset)[8]) {
  using Tables = CompressedTransportTables;
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
    _mm256_storeu_si256(
        reinterpret_cast<__m256i*>(offset[s]),
        _mm256_add_epi32(
            _mm256_slli_epi32(keys[s], 2),
            _mm256_set1_epi32(static_cast<int>(t.bc1_table_offset[static_cast<std::size_t>(s)]))));
}

// The offsets of the `count` (1..8) blocks at `blocks`: 8 at once in
// vectors, fewer (the end of a block row or column) one by one.
__attribute__((target("avx2,fma"))) inline void bc1_offsets(const CompressedTransportTables& t,
                                                            const std::uint8_t* blocks,
                                                            std::size_t count,
                                                            std::uint32_t (*offset)[8]) {
  if (count == 8) return bc1_offsets_x8(t, blocks, offset);
  for (std::size_t j = 0; j < count; ++j) {
    std::uint32_t endpoints;
    std::memcpy(&endpoints, blocks + 8 * j, sizeof endpoints);
    for (std::size_t s = 0; s < static_cast<std::size_t>(t.slots); ++s)
      offset[s][j] = static_cast<std::uint32_t>(
          t.bc1_table_offset[s] +
          4 * bc1_palette_key(endpoints, CompressedTransportTables::bc1_field_shift[s],
                              CompressedTransportTables::bc1_field_bits[s]));
  }
}

}  // namespace bounce
#endif
