#pragma once
// What the run-time product of a compressed multi-bounce matrix reads each
// frame, laid out once from a CompressedMatrix (compress/codec.h) for both
// the C++ path (runtime/compressed_transport.h) and the OpenCL one
// (runtime/compressed_transport_cl.h), and what light-importance temporal
// radiosity reads by block columns (dynamic/compressed_columns.h). Everything is in stored order: block
// rows and columns as in the DDS, rows and columns of the matrix permuted.
//
// Palettes in value space: the 4 (BC1) or 8 (BC4) values a block's indices
// select, after the inverse log step, per palette slot. Slots: 3 for BC1
// with three stored channels (stored channel c in colour c of the block),
// else 1 (BC4; BC1 of one stored channel, which sits in R). They come from
// the existing decoders (decode_bc1_block / decode_bc4_block on the block's
// endpoints with indices 0, 1, 2, ...) and LogQuantizer::decode, so they are
// bit for bit what decompress_channel produces; decoding a texel at run time
// is an index lookup.
//
// BC1: one palette table per slot, not one palette per block. A BC1 colour
// channel's 4 codes depend only on its two endpoint fields (5 or 6 bits) and
// on the block's mode (colour0 > colour1 or not), so every palette the
// matrix can hold is in a table of 2 * 2^(2 bits) entries: 32 KB for R and
// B, 128 KB for G, which stay in L2 cache. A product then reads 8 bytes per
// block instead of 8 + 48 (the 12 palette floats), which is what bounds it
// in memory traffic (docs/benchmarks.md, runtime). BC4's 8-entry palettes
// key on two 8-bit endpoints, a 2 MB table per channel that would not stay
// in cache; BC4 (grey scenes) keeps one palette per block.
//
// Holes. A kept entry replaces the decoded value at its position, and the
// block holds some code there (ours: any code, the encoder ignores it). The
// product adds, for each kept entry, correction = kept - decoded(hole) times
// b: the sum over the block values plus the corrections is the product with
// T~ exactly (up to float rounding of the difference, one ulp of the kept
// value), with no per-texel test in the block loop. The corrections are
// stored per colour (R, G, B) on one pattern, the union of the kept entries
// of the stored channels the colours use (mostly the same positions): one
// column index per position and 3 values (0 where that colour's channel
// keeps nothing), or 1 value with one stored channel, which all colours use.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "compress/codec.h"

namespace bounce {

struct CompressedTransportTables {
  std::size_t n = 0;           // patches
  std::size_t padded = 0;      // n rounded up to 4
  std::size_t block_rows = 0;  // padded / 4 (also block columns)
  DdsFormat format = DdsFormat::kBc1;
  int levels = 4;  // palette entries per slot: 4 (BC1), 8 (BC4)
  int slots = 1;   // palettes per block: 3 (BC1, three stored channels) or 1
  // Palette slot of colour channel k (R, G, B).
  std::array<int, 3> slot_of_colour{0, 0, 0};
  // Correction values per position: 3 (R, G, B) or 1 (one stored channel).
  int correction_width = 3;

  std::vector<std::uint8_t> blocks;  // the DDS blocks, 8 bytes each, block-row-major
  // BC4 only: block_rows^2 * levels values, block (I, J), entry e at
  // (I * block_rows + J) * levels + e. Empty for BC1.
  std::vector<float> palettes;
  // BC1 only: the palette tables, see bc1_palette(). Slot s reads the colour
  // field at bit bc1_field_shift[s] of the endpoints, bc1_field_bits[s] wide,
  // and its table starts at bc1_table_offset[s] in bc1_tables.
  std::vector<float> bc1_tables;
  static constexpr std::array<std::uint32_t, 3> bc1_field_shift{11, 5, 0};
  static constexpr std::array<std::uint32_t, 3> bc1_field_bits{5, 6, 5};
  std::array<std::size_t, 3> bc1_table_offset{0, 0, 0};

  // Corrections in CSR form over the stored rows: the entries of stored row
  // i are correction_ptr[i] .. correction_ptr[i + 1] (padded + 1 offsets;
  // padding rows are empty), sorted by column. correction_index packs the
  // stored column (low 30 bits) and the row within its block row (top 2
  // bits), so a kernel that spreads a block row's entries over work-items
  // knows each entry's row without searching the offsets.
  std::vector<std::uint32_t> correction_ptr;
  std::vector<std::uint32_t> correction_index;
  // entries * correction_width values, colour fastest, plus one trailing 0:
  // a 16-byte load of the last entry's 3 values stays inside the array.
  std::vector<float> correction_value;

  Permutation permutation;  // stored row/column k is patch permutation[k]

  std::size_t corrections() const { return correction_index.size(); }
  // Bytes one product reads from the tables (blocks, palettes or BC1
  // palette tables, corrections).
  std::size_t bytes() const;
  // The palette (levels values) of slot `slot` of block (I, J).
  const float* palette(std::size_t I, std::size_t J, int slot) const;
};

// Entry of a BC1 block's palette in its slot's table: mode (1 for the
// 3-colour mode, colour0 <= colour1), then the two endpoint fields.
inline std::uint32_t bc1_palette_key(std::uint32_t endpoints, std::uint32_t shift,
                                     std::uint32_t bits) {
  const std::uint32_t c0 = endpoints & 0xFFFFu, c1 = endpoints >> 16;
  const std::uint32_t mask = (1u << bits) - 1;
  return (static_cast<std::uint32_t>(c0 <= c1) << (2 * bits)) | (((c0 >> shift) & mask) << bits) |
         ((c1 >> shift) & mask);
}

inline constexpr std::uint32_t kCorrectionColumnMask = (1u << 30) - 1;
inline constexpr int kCorrectionRowShift = 30;

// Lays out `m` for the product. `channel_of_rgb`: stored channel of R, G, B
// (ignored with one stored channel: all three use it). Throws bounce::Error
// when a channel is out of range, or when the matrix is inconsistent (block
// count, permutation size, CSR sizes) or too large for 30-bit columns.
CompressedTransportTables build_compressed_transport_tables(
    const CompressedMatrix& m, const std::array<int, 3>& channel_of_rgb);

}  // namespace bounce
