#include "compress/compressed_transport_tables.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

// Indices 0, 1, 2, ... in texels 0, 1, 2, ...: a block with these indices
// and the endpoints of a real block decodes to that block's palette.
constexpr std::uint8_t kBc1PaletteIndices[4] = {0xE4, 0, 0, 0};  // 0b11'10'01'00
// 3-bit indices 0..7 in texels 0..7: 0xFAC688, little-endian in bytes 2..7.
constexpr std::uint8_t kBc4PaletteIndices[6] = {0x88, 0xC6, 0xFA, 0, 0, 0};

void check(bool ok, const std::string& what) {
  if (!ok) throw Error("compressed transport", what);
}

// Palette index of texel (r, c) (row, column within the block).
int texel_index(const std::uint8_t* block, DdsFormat format, std::size_t r, std::size_t c) {
  if (format == DdsFormat::kBc1) return (block[4 + r] >> (2 * c)) & 3;
  std::uint64_t field = 0;
  for (int k = 0; k < 6; ++k) field |= static_cast<std::uint64_t>(block[2 + k]) << (8 * k);
  return static_cast<int>((field >> (3 * (4 * r + c))) & 7);
}

// BC1: every palette slot s can hold, in a table keyed by bc1_palette_key.
// Each entry is decoded by decode_bc1_block from a probe block whose
// endpoints carry the key's fields in colour s, and, in the other bits, what
// forces the key's mode: colour s's own low bits when it is the top field
// (R), else R. Keys whose mode no block can have (R endpoints e0 < e1 in the
// 4-colour mode, say) stay 0: no block looks them up.
void build_bc1_tables(const CompressedMatrix& m, CompressedTransportTables& t) {
  std::size_t total = 0;
  for (int s = 0; s < t.slots; ++s) {
    const auto slot = static_cast<std::size_t>(s);
    t.bc1_table_offset[slot] = total;
    total += (std::size_t{2} << (2 * t.bc1_field_bits[slot])) * 4;
  }
  t.bc1_tables.assign(total, 0.0f);
  for (int s = 0; s < t.slots; ++s) {
    const auto slot = static_cast<std::size_t>(s);
    const std::uint32_t shift = t.bc1_field_shift[slot], bits = t.bc1_field_bits[slot];
    for (std::uint32_t mode = 0; mode < 2; ++mode)
      for (std::uint32_t e0 = 0; e0 < (1u << bits); ++e0)
        for (std::uint32_t e1 = 0; e1 < (1u << bits); ++e1) {
          std::uint32_t c0 = e0 << shift, c1 = e1 << shift;
          const std::uint32_t low = (1u << 11) - 1, top = 31u << 11;
          if (shift == 11)
            (mode == 0 ? c0 : c1) |= low;
          else
            (mode == 0 ? c0 : c1) |= top;
          const std::uint32_t endpoints = c0 | (c1 << 16);
          const std::uint32_t key = bc1_palette_key(endpoints, shift, bits);
          if (key >> (2 * bits) != mode) continue;  // no block has this mode with these fields
          const std::uint8_t probe[8] = {
              static_cast<std::uint8_t>(c0), static_cast<std::uint8_t>(c0 >> 8),
              static_cast<std::uint8_t>(c1), static_cast<std::uint8_t>(c1 >> 8),
              kBc1PaletteIndices[0],         kBc1PaletteIndices[1],
              kBc1PaletteIndices[2],         kBc1PaletteIndices[3]};
          std::uint8_t rgb[16][3];
          decode_bc1_block(probe, rgb);
          float* out = &t.bc1_tables[t.bc1_table_offset[slot] + 4 * key];
          for (std::size_t e = 0; e < 4; ++e) out[e] = m.quantizers[slot].decode(rgb[e][slot]);
        }
  }
}

// BC4: one palette per block (see the header for why not a table).
void build_bc4_palettes(const CompressedMatrix& m, CompressedTransportTables& t) {
  const std::size_t blocks = t.block_rows * t.block_rows;
  t.palettes.assign(blocks * 8, 0.0f);
#pragma omp parallel for schedule(static)
  for (std::ptrdiff_t b = 0; b < static_cast<std::ptrdiff_t>(blocks); ++b) {
    const std::uint8_t* block = &t.blocks[static_cast<std::size_t>(b) * 8];
    float* out = &t.palettes[static_cast<std::size_t>(b) * 8];
    std::uint8_t probe[8];
    std::copy(block, block + 2, probe);
    std::copy(kBc4PaletteIndices, kBc4PaletteIndices + 6, probe + 2);
    std::uint8_t value[16];
    decode_bc4_block(probe, value);
    for (std::size_t e = 0; e < 8; ++e) out[e] = m.quantizers[0].decode(value[e]);
  }
}

// One kept entry of a colour's channel, in stored order, while merging.
struct KeptEntry {
  std::uint32_t col;
  int colour;  // 0..2; 0 only with one stored channel
  float correction;
};

void build_corrections(const CompressedMatrix& m, const std::array<int, 3>& channel_of_colour,
                       CompressedTransportTables& t) {
  const std::size_t n = t.n, width = static_cast<std::size_t>(t.correction_width);
  const Permutation stored_of = inverse(m.permutation);
  // Colours whose values are stored: one per stored channel used (width 1:
  // the one channel); the values of a channel serve every colour mapped to it.
  std::array<bool, 3> first_of_channel{};
  for (std::size_t k = 0; k < width; ++k) {
    first_of_channel[k] = true;
    for (std::size_t l = 0; l < k; ++l)
      if (channel_of_colour[l] == channel_of_colour[k]) first_of_channel[k] = false;
  }
  std::size_t total = 0;
  for (std::size_t k = 0; k < width; ++k)
    if (first_of_channel[k])
      total += m.kept[static_cast<std::size_t>(channel_of_colour[k])].col.size();
  check(total <= 0xFFFFFFFFu, "more kept entries than 32-bit offsets address");
  t.correction_ptr.assign(t.padded + 1, 0);
  t.correction_index.clear();
  t.correction_index.reserve(total);
  t.correction_value.clear();
  t.correction_value.reserve(total * width + 1);
  std::vector<KeptEntry> row;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t p = m.permutation[i];
    row.clear();
    for (std::size_t k = 0; k < width; ++k) {
      if (!first_of_channel[k]) continue;
      const auto c = static_cast<std::size_t>(channel_of_colour[k]);
      const CsrMatrix& kept = m.kept[c];
      const std::size_t slot = t.slots == 3 ? c : 0;
      for (std::uint32_t e = kept.row_ptr[p]; e < kept.row_ptr[p + 1]; ++e) {
        const std::uint32_t j = stored_of[kept.col[e]];
        const std::size_t block = (i / 4) * t.block_rows + j / 4;
        const int index = texel_index(&t.blocks[block * 8], t.format, i % 4, j % 4);
        const float decoded = t.palette(i / 4, j / 4, static_cast<int>(slot))[index];
        row.push_back({j, static_cast<int>(k), kept.value[e] - decoded});
      }
    }
    std::sort(row.begin(), row.end(),
              [](const KeptEntry& a, const KeptEntry& b) { return a.col < b.col; });
    const std::uint32_t packed_row = static_cast<std::uint32_t>(i % 4) << kCorrectionRowShift;
    for (std::size_t e = 0; e < row.size(); ++e) {
      if (e == 0 || row[e].col != row[e - 1].col) {
        t.correction_index.push_back(row[e].col | packed_row);
        t.correction_value.insert(t.correction_value.end(), width, 0.0f);
      }
      float* values = &t.correction_value[t.correction_value.size() - width];
      for (std::size_t k = 0; k < width; ++k)
        if (channel_of_colour[k] == channel_of_colour[static_cast<std::size_t>(row[e].colour)])
          values[k] = row[e].correction;
    }
    t.correction_ptr[i + 1] = static_cast<std::uint32_t>(t.correction_index.size());
  }
  for (std::size_t i = n; i < t.padded; ++i) t.correction_ptr[i + 1] = t.correction_ptr[n];
  t.correction_value.push_back(0.0f);
}

}  // namespace

const float* CompressedTransportTables::palette(std::size_t I, std::size_t J, int slot) const {
  const std::uint8_t* block = &blocks[(I * block_rows + J) * 8];
  if (format == DdsFormat::kBc4) return &palettes[(I * block_rows + J) * 8];
  const auto s = static_cast<std::size_t>(slot);
  std::uint32_t endpoints;
  std::memcpy(&endpoints, block, sizeof endpoints);
  return &bc1_tables[bc1_table_offset[s] +
                     4 * bc1_palette_key(endpoints, bc1_field_shift[s], bc1_field_bits[s])];
}

std::size_t CompressedTransportTables::bytes() const {
  return blocks.size() + (palettes.size() + bc1_tables.size()) * sizeof(float) +
         (correction_ptr.size() + correction_index.size()) * sizeof(std::uint32_t) +
         correction_value.size() * sizeof(float);
}

CompressedTransportTables build_compressed_transport_tables(
    const CompressedMatrix& m, const std::array<int, 3>& channel_of_rgb) {
  CompressedTransportTables t;
  t.n = m.n;
  t.padded = (m.n + 3) / 4 * 4;
  t.block_rows = t.padded / 4;
  t.format = m.format;
  check(m.channels == 1 || m.channels == 3,
        "the matrix stores " + std::to_string(m.channels) + " channels (1 or 3 expected)");
  // BC4 per channel (3 planes) is a comparison of bounce bench compress, not
  // a bake format: its planes would need a block loop of their own.
  check(m.format == DdsFormat::kBc1 || m.channels == 1,
        "BC4 per channel (one BC4 image per stored channel) is not supported: bakes store "
        "BC1 for colour and BC4 for one channel");
  check(m.padded == t.padded,
        "padded size " + std::to_string(m.padded) + " for " + std::to_string(m.n) + " patches");
  check(m.blocks.size() == t.block_rows * t.block_rows * 8,
        std::to_string(m.blocks.size()) + " block bytes for a " + std::to_string(t.padded) +
            "^2 image");
  check(m.permutation.size() == m.n && is_bijection(m.permutation),
        "the permutation is not a permutation of the " + std::to_string(m.n) + " patches");
  check(m.quantizers.size() == static_cast<std::size_t>(m.channels) &&
            m.kept.size() == static_cast<std::size_t>(m.channels),
        "quantizers or kept parts do not match the channel count");
  for (const CsrMatrix& k : m.kept) {
    check(k.row_ptr.size() == m.n + 1 && k.col.size() == k.value.size() &&
              k.row_ptr.back() == k.col.size(),
          "a kept (CSR) part does not match the matrix size");
    for (std::uint32_t c : k.col) check(c < m.n, "a kept entry's column is out of range");
  }
  // The column shares a 32-bit word with the row within the block row.
  check(t.padded <= kCorrectionColumnMask,
        std::to_string(m.n) + " patches exceed the 30-bit column index of the corrections");
  std::array<int, 3> channel_of_colour{};
  for (std::size_t k = 0; k < 3; ++k) {
    const int c = m.channels == 1 ? 0 : channel_of_rgb[k];
    check(c >= 0 && c < m.channels, "channel_of_rgb maps colour " + std::to_string(k) +
                                        " to stored channel " + std::to_string(c) + " of " +
                                        std::to_string(m.channels));
    channel_of_colour[k] = c;
  }
  if (m.format == DdsFormat::kBc1) {
    t.levels = 4;
    t.slots = m.channels;
  } else {
    t.levels = 8;
    t.slots = 1;
  }
  for (std::size_t k = 0; k < 3; ++k) t.slot_of_colour[k] = t.slots == 3 ? channel_of_colour[k] : 0;
  t.correction_width = m.channels == 1 ? 1 : 3;
  t.blocks = m.blocks;
  t.permutation = m.permutation;
  if (t.format == DdsFormat::kBc1)
    build_bc1_tables(m, t);
  else
    build_bc4_palettes(m, t);
  build_corrections(m, channel_of_colour, t);
  return t;
}

}  // namespace bounce
