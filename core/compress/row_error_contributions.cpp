#include "compress/row_error_contributions.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "base/error.h"

namespace bounce {

namespace {

constexpr const char* kWhere = "row error contributions";

// The 8-bit codes of stored row `i` of stored channel `c`, one per stored
// column (padded), decoded from the row's blocks only: the same texels
// decode_blocks_of_channel reads from the whole image.
std::vector<std::uint8_t> stored_row_codes(const CompressedMatrix& m, int c, std::size_t i) {
  const std::size_t w = m.padded, blocks_per_row = w / 4;
  const bool bc4 = m.format == DdsFormat::kBc4;
  const std::size_t images = bc4 ? static_cast<std::size_t>(m.channels) : 1;
  const std::size_t image_bytes = blocks_per_row * blocks_per_row * kBc1BlockBytes;
  if (m.blocks.size() != images * image_bytes)
    throw Error(kWhere, "the block image holds " + std::to_string(m.blocks.size()) +
                            " bytes, expected " + std::to_string(images * image_bytes));
  // BC4 with several stored channels: one image per channel. BC1 with one
  // stored channel (a grey scene in the published pipeline) keeps it in R.
  const std::size_t image = bc4 && m.channels > 1 ? static_cast<std::size_t>(c) : 0;
  const std::size_t colour = bc4 || m.channels == 1 ? 0 : static_cast<std::size_t>(c);
  const std::size_t y = i % 4;
  std::vector<std::uint8_t> codes(w);
  for (std::size_t bx = 0; bx < blocks_per_row; ++bx) {
    const std::uint8_t* block =
        &m.blocks[image * image_bytes + ((i / 4) * blocks_per_row + bx) * kBc1BlockBytes];
    if (bc4) {
      std::uint8_t value[16];
      decode_bc4_block(block, value);
      for (std::size_t x = 0; x < 4; ++x) codes[bx * 4 + x] = value[y * 4 + x];
    } else {
      std::uint8_t rgb[16][3];
      decode_bc1_block(block, rgb);
      for (std::size_t x = 0; x < 4; ++x) codes[bx * 4 + x] = rgb[y * 4 + x][colour];
    }
  }
  return codes;
}

}  // namespace

RowErrorContributions row_error_contributions(const CompressedMatrix& m,
                                              const std::vector<const float*>& exact,
                                              const std::array<int, 3>& channel_of_rgb,
                                              const std::vector<glm::vec3>& b, std::size_t patch) {
  const std::size_t n = m.n;
  if (patch >= n)
    throw Error(kWhere, "patch " + std::to_string(patch) + " is not one of the matrix's " +
                            std::to_string(n));
  if (b.size() != n)
    throw Error(kWhere, "the light has " + std::to_string(b.size()) + " patches, the matrix " +
                            std::to_string(n));
  if (exact.size() != static_cast<std::size_t>(m.channels) || m.quantizers.size() != exact.size() ||
      m.kept.size() != exact.size() || m.permutation.size() != n || m.padded < n ||
      m.padded % 4 != 0)
    throw Error(kWhere,
                "the exact matrices, quantisers, kept entries or permutation do not "
                "match the compressed matrix's " +
                    std::to_string(m.channels) + " channels of " + std::to_string(n));
  for (const int c : channel_of_rgb)
    if (c < 0 || c >= m.channels)
      throw Error(kWhere, "colour uses stored channel " + std::to_string(c) + " of " +
                              std::to_string(m.channels));

  RowErrorContributions r;
  r.patch = patch;
  r.stored_row = static_cast<std::size_t>(
      std::find(m.permutation.begin(), m.permutation.end(), patch) - m.permutation.begin());
  if (r.stored_row == n) throw Error(kWhere, "the permutation does not hold the patch");

  // Per stored channel: the row in patch order as decoded (kept entries
  // replacing the block's value) and which of its columns are kept.
  const auto channels = static_cast<std::size_t>(m.channels);
  std::vector<std::vector<double>> decoded(channels, std::vector<double>(n));
  std::vector<std::vector<char>> kept(channels, std::vector<char>(n, 0));
  for (std::size_t c = 0; c < channels; ++c) {
    const std::vector<std::uint8_t> codes = stored_row_codes(m, static_cast<int>(c), r.stored_row);
    for (std::size_t k = 0; k < n; ++k)
      decoded[c][m.permutation[k]] = m.quantizers[c].decode(codes[k]);
    const CsrMatrix& csr = m.kept[c];
    if (csr.row_ptr.size() != n + 1)
      throw Error(kWhere, "kept entries of channel " + std::to_string(c) + " are not " +
                              std::to_string(n) + " rows");
    for (std::uint32_t e = csr.row_ptr[patch]; e < csr.row_ptr[patch + 1]; ++e) {
      decoded[c][csr.col[e]] = csr.value[e];
      kept[c][csr.col[e]] = 1;
    }
  }

  const auto entry_of = [&](std::size_t k) {
    RowEntry e;
    e.stored_col = k;
    e.column = m.permutation[k];
    for (std::size_t colour = 0; colour < 3; ++colour) {
      const auto c = static_cast<std::size_t>(channel_of_rgb[colour]);
      e.exact[static_cast<int>(colour)] = exact[c][patch * n + e.column];
      e.decoded[static_cast<int>(colour)] = decoded[c][e.column];
    }
    return e;
  };
  const auto kept_in_colour = [&](std::size_t j, int colour) {
    return kept[static_cast<std::size_t>(channel_of_rgb[static_cast<std::size_t>(colour)])][j] != 0;
  };

  std::map<std::size_t, RowErrorSource> blocks;  // by block column
  for (std::size_t k = 0; k < n; ++k) {
    const RowEntry e = entry_of(k);
    const std::size_t j = e.column;
    const glm::dvec3 light(b[j]);
    r.exact += e.exact * light;
    r.compressed += e.decoded * light;
    RowErrorSource kept_source;
    kept_source.kind = RowErrorSource::Kind::Kept;
    RowErrorSource& block = blocks[k / 4];
    block.kind = RowErrorSource::Kind::Block;
    bool in_block = false, in_kept = false;
    for (int colour = 0; colour < 3; ++colour) {
      const double term = (e.decoded[colour] - e.exact[colour]) * light[colour];
      if (kept_in_colour(j, colour)) {
        kept_source.contribution[colour] += term;
        in_kept = true;
      } else {
        block.contribution[colour] += term;
        in_block = true;
      }
    }
    if (in_block) block.entries.push_back(e);
    if (in_kept) {
      kept_source.entries.push_back(e);
      kept_source.block_row = r.stored_row / 4;
      kept_source.block_col = k / 4;
      r.sources.push_back(std::move(kept_source));
    }
  }
  for (auto& [block_col, source] : blocks) {
    source.block_row = r.stored_row / 4;
    source.block_col = block_col;
    const bool nonzero =
        source.contribution != glm::dvec3(0.0) ||
        std::any_of(source.entries.begin(), source.entries.end(), [](const RowEntry& e) {
          return e.exact != glm::dvec3(0.0) || e.decoded != glm::dvec3(0.0);
        });
    if (!source.entries.empty() && nonzero) r.sources.push_back(std::move(source));
  }

  r.difference = r.compressed - r.exact;
  const double d2 = glm::dot(r.difference, r.difference);
  for (RowErrorSource& s : r.sources)
    s.share = d2 > 0.0 ? glm::dot(s.contribution, r.difference) / d2 : 0.0;
  std::stable_sort(r.sources.begin(), r.sources.end(),
                   [](const RowErrorSource& a, const RowErrorSource& c) {
                     if (a.share != c.share) return a.share > c.share;
                     return glm::length(a.contribution) > glm::length(c.contribution);
                   });
  return r;
}

}  // namespace bounce
