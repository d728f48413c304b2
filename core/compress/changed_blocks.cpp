#include "compress/changed_blocks.h"

#include <algorithm>

#include "base/error.h"
#include "compress/block_bc1.h"
#include "compress/block_bc4.h"

namespace bounce {

namespace {

// Sample slot of each block row of the image (every block row when not
// sampled); -1 for rows the compression does not hold.
std::vector<std::int64_t> slot_of_block_row(const CompressedMatrix& m) {
  std::vector<std::int64_t> slot(m.padded / 4, -1);
  if (!m.sampled()) {
    for (std::size_t b = 0; b < slot.size(); ++b) slot[b] = static_cast<std::int64_t>(b);
  } else {
    for (std::size_t s = 0; s < m.block_rows.size(); ++s)
      slot[m.block_rows[s]] = static_cast<std::int64_t>(s);
  }
  return slot;
}

// Calls mark(j) for every column kept in exactly one of the two sorted rows.
template <class Mark>
void symmetric_difference(std::span<const std::uint32_t> a, std::span<const std::uint32_t> b,
                          Mark mark) {
  std::size_t x = 0, y = 0;
  while (x < a.size() || y < b.size()) {
    if (y == b.size() || (x < a.size() && a[x] < b[y])) {
      mark(a[x++]);
    } else if (x == a.size() || b[y] < a[x]) {
      mark(b[y++]);
    } else {
      ++x;
      ++y;
    }
  }
}

std::span<const std::uint32_t> kept_row(const CsrMatrix& k, std::size_t i) {
  return std::span(k.col).subspan(k.row_ptr[i], k.row_ptr[i + 1] - k.row_ptr[i]);
}

}  // namespace

std::vector<std::size_t> blocks_with_changed_holes(const CompressedMatrix& before,
                                                   const CompressedMatrix& after) {
  if (before.n != after.n || before.permutation != after.permutation ||
      before.block_rows != after.block_rows || before.kept.size() != after.kept.size())
    throw Error("compress", "changed blocks: the two compressions do not share their layout");
  const std::size_t per_row = after.padded / 4;
  const std::vector<std::int64_t> slot = slot_of_block_row(after);
  const Permutation place = inverse(after.permutation);  // stored index of each patch
  const std::vector<std::uint32_t> rows = after.rows();
  std::vector<std::uint8_t> changed(after.blocks.size() / 8, 0);
  for (std::size_t c = 0; c < after.kept.size(); ++c)
    for (const std::uint32_t i : rows) {
      const auto s = static_cast<std::size_t>(slot[place[i] / 4]);
      symmetric_difference(kept_row(before.kept[c], i), kept_row(after.kept[c], i),
                           [&](std::uint32_t j) { changed[s * per_row + place[j] / 4] = 1; });
    }
  std::vector<std::size_t> which;
  for (std::size_t b = 0; b < changed.size(); ++b)
    if (changed[b]) which.push_back(b);
  return which;
}

void encode_blocks_in_place(const BlockEncoding& e, std::span<const std::size_t> which,
                            std::span<const std::uint8_t> codes, std::span<const float> weights,
                            std::size_t channels, CompressedMatrix& m,
                            std::span<const std::uint32_t> row_slot) {
  if (e.images() != 1 || channels != e.texel_channels())
    throw Error("compress", "blocks are re-encoded in place in one image only");
  const std::size_t n = m.n, per_row = m.padded / 4;
  const std::vector<std::uint32_t> rows = m.sampled() ? m.block_rows : std::vector<std::uint32_t>();
  const bool bc4 = e.format == DdsFormat::kBc4;
#pragma omp parallel for schedule(dynamic, 64)
  for (std::size_t k = 0; k < which.size(); ++k) {
    const std::size_t slot = which[k] / per_row, bx = which[k] % per_row;
    const std::size_t by = rows.empty() ? slot : rows[slot];
    std::uint8_t texel[16][3] = {};
    float weight[16][3] = {};
    for (std::size_t y = 0; y < 4; ++y)
      for (std::size_t x = 0; x < 4; ++x) {
        const std::size_t i = 4 * by + y, j = 4 * bx + x;
        if (i >= n || j >= n) continue;  // padding: code 0, weight 0
        const std::size_t row = m.permutation[i];
        const std::size_t texel_row = row_slot.empty() ? row : row_slot[row];
        const std::size_t src = (texel_row * n + m.permutation[j]) * channels;
        for (std::size_t c = 0; c < channels; ++c) {
          texel[4 * y + x][c] = codes[src + c];
          weight[4 * y + x][c] = weights[src + c];
        }
      }
    std::uint8_t* out = &m.blocks[which[k] * 8];
    if (bc4) {
      std::uint8_t value[16];
      float w[16];
      for (int t = 0; t < 16; ++t) {
        value[t] = texel[t][0];
        w[t] = weight[t][0];
      }
      encode_bc4_block(Bc4Encoder::kWeighted, value, w, out);
    } else {
      encode_bc1_block(e.bc1, texel, weight, out);
    }
  }
}

}  // namespace bounce
