#include "dynamic/compressed_columns.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>

#include "compress/bc1_palette_offsets.h"
#endif

namespace bounce {

namespace {

using Tables = CompressedTransportTables;

// Blocks below which a loop runs on one thread.
constexpr std::size_t kParallelBlocks = 65536;

// The block's index word: 2-bit codes in bytes 4..7 (BC1), 3-bit codes in
// bytes 2..7 (BC4); texel (r, c) is code 4 r + c.
std::uint64_t block_indices(const Tables& t, const std::uint8_t* block) {
  if (t.format == DdsFormat::kBc1) {
    std::uint32_t v;
    std::memcpy(&v, block + 4, sizeof v);
    return v;
  }
  std::uint64_t v;
  std::memcpy(&v, block, sizeof v);
  return v >> 16;
}

int code_bits(const Tables& t) { return t.format == DdsFormat::kBc1 ? 2 : 3; }

// The palettes of colours R, G, B of block (I, J) (what t.palette gives,
// inlined for BC1: a frame decodes one block per drawn column and block row).
// `block`: its 8 bytes, wherever they are stored.
void block_palettes(const Tables& t, const std::uint8_t* block, std::size_t I, std::size_t J,
                    const float* (&palette)[3]) {
  if (t.format != DdsFormat::kBc1) {
    for (std::size_t k = 0; k < 3; ++k) palette[k] = t.palette(I, J, 0);
    return;
  }
  std::uint32_t endpoints;
  std::memcpy(&endpoints, block, sizeof endpoints);
  for (std::size_t k = 0; k < 3; ++k) {
    const auto s = static_cast<std::size_t>(t.slots == 1 ? 0 : t.slot_of_colour[k]);
    palette[k] = &t.bc1_tables[t.bc1_table_offset[s] +
                               4 * bc1_palette_key(endpoints, Tables::bc1_field_shift[s],
                                                   Tables::bc1_field_bits[s])];
  }
}

// The decoded (block) value of stored entry (i, j) in each colour.
void decoded_entry(const Tables& t, std::size_t i, std::size_t j, float (&v)[3]) {
  const std::size_t I = i / 4, J = j / 4;
  const std::uint8_t* block = &t.blocks[(I * t.block_rows + J) * 8];
  const std::uint64_t indices = block_indices(t, block);
  const int bits = code_bits(t);
  const auto e =
      static_cast<std::size_t>((indices >> (bits * (4 * (i % 4) + j % 4))) & ((1u << bits) - 1));
  const float* palette[3];
  block_palettes(t, block, I, J, palette);
  for (std::size_t k = 0; k < 3; ++k) v[k] = palette[k][e];
}

}  // namespace

std::vector<float> compressed_column_abs_sums(const Tables& t) {
  std::vector<float> sums(3 * t.padded, 0.0f);
  const std::size_t nb = t.block_rows;
  const int bits = code_bits(t);
  const std::uint64_t mask = (1u << bits) - 1;
  // Block columns in parallel, each summing its 4 columns in float64.
  const auto columns = static_cast<std::ptrdiff_t>(nb);
#pragma omp parallel for schedule(dynamic, 8) if (nb * nb >= kParallelBlocks)
  for (std::ptrdiff_t sj = 0; sj < columns; ++sj) {
    const auto J = static_cast<std::size_t>(sj);
    double acc[4][3] = {};
    for (std::size_t I = 0; I < nb; ++I) {
      const std::uint8_t* block = &t.blocks[(I * nb + J) * 8];
      const std::uint64_t indices = block_indices(t, block);
      const float* palette[3];
      block_palettes(t, block, I, J, palette);
      for (int r = 0; r < 4; ++r) {
        if (4 * I + static_cast<std::size_t>(r) >= t.n) break;  // padding rows
        for (int c = 0; c < 4; ++c) {
          const auto e = static_cast<std::size_t>((indices >> (bits * (4 * r + c))) & mask);
          for (std::size_t k = 0; k < 3; ++k) acc[c][k] += std::abs(palette[k][e]);
        }
      }
    }
    for (std::size_t c = 0; c < 4; ++c)
      for (std::size_t k = 0; k < 3; ++k) sums[3 * (4 * J + c) + k] = static_cast<float>(acc[c][k]);
  }
  // Kept entries replace their hole's decoded value: swap |decoded| for
  // |kept| (kept = decoded + correction). Serial: columns collide.
  const int width = t.correction_width;
  for (std::size_t i = 0; i < t.n; ++i)
    for (std::uint32_t e = t.correction_ptr[i]; e < t.correction_ptr[i + 1]; ++e) {
      const std::size_t j = t.correction_index[e] & kCorrectionColumnMask;
      float decoded[3];
      decoded_entry(t, i, j, decoded);
      for (std::size_t k = 0; k < 3; ++k) {
        const float correction =
            t.correction_value[static_cast<std::size_t>(width) * e + (width == 3 ? k : 0)];
        float& s = sums[3 * j + k];
        s = std::max(0.0f, s - std::abs(decoded[k]) + std::abs(decoded[k] + correction));
      }
    }
  for (std::size_t j = t.n; j < t.padded; ++j)
    for (std::size_t k = 0; k < 3; ++k) sums[3 * j + k] = 0.0f;
  return sums;
}

KeptColumns kept_by_column(const Tables& t) {
  KeptColumns k;
  k.width = t.correction_width;
  const std::size_t entries = t.corrections();
  k.ptr.assign(t.padded + 1, 0);
  for (std::size_t e = 0; e < entries; ++e)
    ++k.ptr[(t.correction_index[e] & kCorrectionColumnMask) + 1];
  for (std::size_t j = 0; j < t.padded; ++j) k.ptr[j + 1] += k.ptr[j];
  k.row.resize(entries);
  // One trailing 0: a 4-wide load of the last entry's 3 values stays inside.
  k.value.assign(entries * static_cast<std::size_t>(k.width) + 1, 0.0f);
  std::vector<std::uint32_t> next(k.ptr.begin(), k.ptr.end() - 1);
  const auto width = static_cast<std::size_t>(k.width);
  for (std::size_t i = 0; i < t.padded; ++i)
    for (std::uint32_t e = t.correction_ptr[i]; e < t.correction_ptr[i + 1]; ++e) {
      const std::uint32_t slot = next[t.correction_index[e] & kCorrectionColumnMask]++;
      k.row[slot] = static_cast<std::uint32_t>(i);
      for (std::size_t c = 0; c < width; ++c)
        k.value[width * slot + c] = t.correction_value[width * e + c];
    }
  return k;
}

namespace {

#if defined(__x86_64__) || defined(__i386__)
// BC1 with AVX2, as the runtime's product decodes a block: the index word,
// shifted by a different amount in each of 8 lanes, is the control of an
// in-lane permute of the palette (broadcast to both lanes; the permute reads
// only the low 2 bits of each lane), giving rows r and r + 1 of the block in
// one register; x of the block's 4 columns, colour-major in `xs` (12 floats
// per drawn block column), is broadcast to both lanes and multiplied in.
// Accumulators per row pair and colour; the 4 columns are summed at the end.
// Block rows go in groups of 8: a drawn column's 8 blocks of the group are
// consecutive, so their palette offsets are computed 8 at once
// (compress/bc1_palette_offsets.h) before the rows read them; one block at a
// time, the scalar keys cost as much as the rest of the block.
__attribute__((target("avx2,fma"))) void multiply_bc1_avx2(
    const Tables& t, const std::uint8_t* column_blocks, const float* xs,
    std::span<const std::uint32_t> block_columns, float (*y)[4], bool parallel) {
  const std::size_t nb = t.block_rows;
  const std::size_t drawn = block_columns.size();
  const auto groups = static_cast<std::ptrdiff_t>((nb + 7) / 8);
  const std::array<std::size_t, 3> slot{
      static_cast<std::size_t>(t.slots == 1 ? 0 : t.slot_of_colour[0]),
      static_cast<std::size_t>(t.slots == 1 ? 0 : t.slot_of_colour[1]),
      static_cast<std::size_t>(t.slots == 1 ? 0 : t.slot_of_colour[2])};
  const float* tables = t.bc1_tables.data();
#pragma omp parallel if (parallel)
  {
    // [drawn column][slot][block of the group]
    std::vector<std::uint32_t> offsets(24 * drawn);
#pragma omp for schedule(dynamic, 4)
    for (std::ptrdiff_t g = 0; g < groups; ++g) {
      const std::size_t I0 = 8 * static_cast<std::size_t>(g);
      const std::size_t count = std::min<std::size_t>(8, nb - I0);
      for (std::size_t d = 0; d < drawn; ++d)
        bc1_offsets(t, column_blocks + 8 * (block_columns[d] * nb + I0), count,
                    reinterpret_cast<std::uint32_t(*)[8]>(&offsets[24 * d]));
      const __m256i shift01 = _mm256_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14);
      const __m256i shift23 = _mm256_setr_epi32(16, 18, 20, 22, 24, 26, 28, 30);
      for (std::size_t lane = 0; lane < count; ++lane) {
        const std::size_t I = I0 + lane;
        __m256 a01[3] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
        __m256 a23[3] = {_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
        for (std::size_t d = 0; d < drawn; ++d) {
          const std::uint8_t* block = column_blocks + 8 * (block_columns[d] * nb + I);
          std::uint32_t indices;
          std::memcpy(&indices, block + 4, 4);
          const __m256i word = _mm256_set1_epi32(static_cast<int>(indices));
          const __m256i c01 = _mm256_srlv_epi32(word, shift01);
          const __m256i c23 = _mm256_srlv_epi32(word, shift23);
          const std::uint32_t* offset = &offsets[24 * d + lane];
          for (std::size_t k = 0; k < 3; ++k) {
            const __m256 p =
                _mm256_broadcast_ps(reinterpret_cast<const __m128*>(tables + offset[8 * slot[k]]));
            const __m256 xk =
                _mm256_broadcast_ps(reinterpret_cast<const __m128*>(xs + 12 * d + 4 * k));
            a01[k] = _mm256_fmadd_ps(_mm256_permutevar_ps(p, c01), xk, a01[k]);
            a23[k] = _mm256_fmadd_ps(_mm256_permutevar_ps(p, c23), xk, a23[k]);
          }
        }
        for (std::size_t k = 0; k < 3; ++k) {
          alignas(32) float v01[8], v23[8];
          _mm256_store_ps(v01, a01[k]);
          _mm256_store_ps(v23, a23[k]);
          y[4 * I][k] = (v01[0] + v01[1]) + (v01[2] + v01[3]);
          y[4 * I + 1][k] = (v01[4] + v01[5]) + (v01[6] + v01[7]);
          y[4 * I + 2][k] = (v23[0] + v23[1]) + (v23[2] + v23[3]);
          y[4 * I + 3][k] = (v23[4] + v23[5]) + (v23[6] + v23[7]);
        }
        for (std::size_t r = 0; r < 4; ++r) y[4 * I + r][3] = 0.0f;
      }
    }
  }
}
#endif

}  // namespace

std::vector<std::uint8_t> blocks_by_column(const Tables& t) {
  const std::size_t nb = t.block_rows;
  std::vector<std::uint8_t> out(t.blocks.size());
  for (std::size_t I = 0; I < nb; ++I)
    for (std::size_t J = 0; J < nb; ++J)
      std::memcpy(&out[8 * (J * nb + I)], &t.blocks[8 * (I * nb + J)], 8);
  return out;
}

void multiply_block_columns(const Tables& t, const std::uint8_t* column_blocks, const float* x,
                            std::span<const std::uint32_t> block_columns, float (*y)[4]) {
  const std::size_t nb = t.block_rows;
  // Threads only where the work outweighs waking them (on a loaded machine
  // a parallel region can wait a scheduler slice for its second thread).
  const bool parallel = block_columns.size() * nb >= kParallelBlocks;
#if defined(__x86_64__) || defined(__i386__)
  if (t.format == DdsFormat::kBc1 && __builtin_cpu_supports("avx2") &&
      __builtin_cpu_supports("fma")) {
    std::vector<float> xs(12 * block_columns.size());
    for (std::size_t d = 0; d < block_columns.size(); ++d)
      for (std::size_t c = 0; c < 4; ++c)
        for (std::size_t k = 0; k < 3; ++k)
          xs[12 * d + 4 * k + c] = x[4 * (4 * static_cast<std::size_t>(block_columns[d]) + c) + k];
    multiply_bc1_avx2(t, column_blocks, xs.data(), block_columns, y, parallel);
    return;
  }
#endif
  const int bits = code_bits(t);
  const std::uint64_t mask = (1u << bits) - 1;
  const auto rows = static_cast<std::ptrdiff_t>(nb);
#pragma omp parallel for schedule(dynamic, 32) if (parallel)
  for (std::ptrdiff_t si = 0; si < rows; ++si) {
    const auto I = static_cast<std::size_t>(si);
    float acc[4][3] = {};
    for (std::uint32_t J : block_columns) {
      const std::uint8_t* block = column_blocks + 8 * (static_cast<std::size_t>(J) * nb + I);
      const std::uint64_t indices = block_indices(t, block);
      const float* palette[3];
      block_palettes(t, block, I, J, palette);
      const float* xb = x + 16 * static_cast<std::size_t>(J);
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) {
          const auto e = static_cast<std::size_t>((indices >> (bits * (4 * r + c))) & mask);
          for (std::size_t k = 0; k < 3; ++k) acc[r][k] += palette[k][e] * xb[4 * c + k];
        }
    }
    for (std::size_t r = 0; r < 4; ++r) {
      for (std::size_t k = 0; k < 3; ++k) y[4 * I + r][k] = acc[r][k];
      y[4 * I + r][3] = 0.0f;
    }
  }
}

std::size_t add_kept_columns(const KeptColumns& kept, const float* x,
                             std::span<const std::uint32_t> block_columns, float (*y)[4]) {
  // Serial: the entries of a few columns scatter over all rows, and they are
  // few (the drawn columns' share of the kept entries). Rows of 4 floats:
  // an entry is one 4-wide multiply-add into its row, the fourth lane
  // multiplied by the column's x with its fourth lane cleared (with 3 values
  // per entry, the 4-wide load of the values reads the next entry's first
  // value, or the trailing 0, into that lane).
  const auto width = static_cast<std::size_t>(kept.width);
  std::size_t added = 0;
  for (std::uint32_t J : block_columns)
    for (std::size_t q = 4 * static_cast<std::size_t>(J); q < 4 * static_cast<std::size_t>(J) + 4;
         ++q) {
      const std::uint32_t first = kept.ptr[q], last = kept.ptr[q + 1];
      added += last - first;
#if defined(__SSE2__)
      const __m128 xq = _mm_setr_ps(x[4 * q], x[4 * q + 1], x[4 * q + 2], 0.0f);
      if (width == 3) {
        for (std::uint32_t e = first; e < last; ++e) {
          float* out = y[kept.row[e]];
          const __m128 v = _mm_loadu_ps(&kept.value[3 * static_cast<std::size_t>(e)]);
          _mm_storeu_ps(out, _mm_add_ps(_mm_loadu_ps(out), _mm_mul_ps(v, xq)));
        }
      } else {
        for (std::uint32_t e = first; e < last; ++e) {
          float* out = y[kept.row[e]];
          const __m128 v = _mm_set1_ps(kept.value[e]);
          _mm_storeu_ps(out, _mm_add_ps(_mm_loadu_ps(out), _mm_mul_ps(v, xq)));
        }
      }
#else
      const float* xq = x + 4 * q;
      for (std::uint32_t e = first; e < last; ++e) {
        const float* v = &kept.value[width * e];
        float* out = y[kept.row[e]];
        for (std::size_t k = 0; k < 3; ++k) out[k] += v[width == 3 ? k : 0] * xq[k];
      }
#endif
    }
  return added;
}

}  // namespace bounce
