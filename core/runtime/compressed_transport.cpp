#include "runtime/compressed_transport.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "base/error.h"
#include "runtime/block_loops.h"

namespace bounce {

using block_loops::BlockBandFn;
using block_loops::BlockRowInput;
using block_loops::CorrectionsFn;
using block_loops::kBandRows;
using block_loops::load_u32;
using Tables = CompressedTransportTables;

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
            block_loops::cpu_has_avx2()),
      avx512_((loop == BlockLoop::kFastest || loop == BlockLoop::kFloat32) &&
              block_loops::cpu_has_avx512()),
      bf16_(loop == BlockLoop::kFastest && tables_.format == DdsFormat::kBc1 &&
            block_loops::cpu_has_avx512_bf16()),
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
      Bc1BlockPair& pair = block_pairs_[block_loops::pair_record(nb, pairs_per_row_, I, J / 2)];
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
      Bc1BlockGroup& group = block_groups_[block_loops::group_record(nb, groups_per_row_, I, G)];
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

bool CompressedTransport::has_bf16_loop() { return block_loops::cpu_has_avx512_bf16(); }

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
  const BlockBandFn block_band = block_loops::block_band_function(t, avx2_, avx512_, bf16_);
  const CorrectionsFn corrections = block_loops::corrections_function(t, avx2_);
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
